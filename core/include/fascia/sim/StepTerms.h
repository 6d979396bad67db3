#pragma once
/// Integrators and constraints described by their terms, for a step backend that runs them on its
/// device (the cuda plugin's CudaStep, docs/design.md section 4.7), as fascia/sim/LoadTerms.h
/// describes loads: implemented beside BaseIntegrator and BaseConstraint by the components that
/// are such terms (the mechanics plugin's) and found with dynamic_cast, so that a backend names no
/// class and reads no parameter by name, and the roles of fascia/sim/Mechanics.h stay as they are.

namespace fascia::core {

/// An explicit integrator whose update is one of the standard schemes below, with mass-proportional
/// damping alpha (m x'' + alpha m x' + f_int = f_ext).
class ExplicitScheme {
public:
    enum class Update {
        /// v += kick (f/m - alpha v), x += dt v; the first kick dt/2 with halfStepStart (the
        /// leapfrog start), then (dt_old + dt)/2; without it dt
        SemiImplicitEuler,
        /// x(n+1) = [2 x(n) - (1 - alpha dt/2) x(n-1) + dt^2 f(n)/m] / (1 + alpha dt/2), restarted
        /// at the first step and after a change of dt
        CentralDifference,
    };
    struct Terms {
        Update update = Update::SemiImplicitEuler;
        double damping = 0;         ///< alpha (1/s)
        bool halfStepStart = true;  ///< SemiImplicitEuler's first kick over dt/2
    };
    virtual ~ExplicitScheme();
    virtual Terms schemeTerms() const = 0;
};

/// A constraint that only holds axes of nodes: on each axis of its constrainedAxes() at each node
/// of its constrainedNodes() its projections set the position and the velocity (the rest position
/// and zero, or, when it prescribesMotion(), what projectState gives at the time) and remove the
/// force, and it does nothing else. A backend runs it from those lists (and projectState).
class AxisHold {
public:
    virtual ~AxisHold();
};

} // namespace fascia::core
