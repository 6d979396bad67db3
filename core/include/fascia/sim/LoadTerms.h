#pragma once
/// Loads described by their terms, for a step backend that applies them on its device (the cuda
/// plugin's CudaStep). Implemented beside BaseForceField by the force fields that are such loads
/// and found with dynamic_cast, as LayoutReport, so that BaseForceField stays as it is.
#include "fascia/base/Types.h"

#include <array>
#include <vector>

namespace fascia::core {

/// A load c(t) F_i on a fixed set of nodes (ConstantForce).
class NodalLoad {
public:
    virtual ~NodalLoad();
    /// The loaded nodes and the force on each at c = 1 (N), as addForce adds them.
    virtual void unscaledLoad(IndexList& nodes, Positions& forces) const = 0;
    /// The load factor c(t) at time t (s): 1 without a curve.
    virtual double loadFactor(double t) const = 0;
    /// Whether c(t) may change with time; false when it is 1 at all times (no load curve), so that
    /// a backend may add the load once to its constant external force. Default: true.
    virtual bool curved() const { return true; }
};

/// A follower pressure c(t) p on boundary faces (SurfacePressure): each triangle carries -p A n, a
/// third on each corner, each quadrilateral the forces of its bilinear patch
/// (fascia/elements/Pressure.h, which both the force field and the device step call).
class PressureLoad {
public:
    virtual ~PressureLoad();
    /// The loaded triangles, each turned outwards.
    virtual const Triangles& pressureTriangles() const = 0;
    /// The loaded quadrilaterals, each counterclockwise seen from outside.
    virtual const std::vector<std::array<int, 4>>& pressureQuads() const = 0;
    /// c(t) p at time t (Pa).
    virtual double pressureAt(double t) const = 0;
};

} // namespace fascia::core
