#pragma once
#include "SurfaceSeries.h"
#include "fascia/sim/Mechanics.h"

#include <array>
#include <vector>

namespace fascia::meshio {

/// A finer visual surface (STL, OBJ or .vtp) moved with a tetrahedral body, as SOFA's BarycentricMapping
/// does for rendering a smooth organ on a coarse volume mesh. At init each vertex is located in a
/// tetrahedron of the body at rest (TetLocator: a grid of buckets, not a search over every
/// tetrahedron); a vertex just outside the body takes the tetrahedron under its nearest boundary
/// triangle, with barycentric weights extrapolated past it (so an affine motion of the body moves
/// it exactly too). After every step (and at the start) each vertex becomes the weighted sum of its
/// tetrahedron's four nodes, x_v = sum_i w_i x_i, on the OpenMP threads in fixed chunks (each
/// vertex alone: the same result for any thread count). The moved surface is read through
/// Simulation::surface("<name>"); with `output` set it is also written as a .vtp series
/// (<output>.pvd, point data displacement) every `every` steps, the initial and final state
/// included.
class BarycentricSurfaceMapping : public core::BaseVisualSurface {
public:
    void init() override;
    void observe(double t, long step) override;
    void observeFinal(double t, long step) override;
    void cleanup() override;
    /// Its .vtp series (the files so far and the last step written): a restored run continues it.
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;
    const core::BaseMechanicalState* body() const override { return m_st; }

    /// Per vertex: its tetrahedron, weights and distance from the body at rest (0 inside).
    const std::vector<int>& vertexTetrahedra() const { return m_tet; }
    const std::vector<std::array<double, 4>>& vertexWeights() const { return m_weights; }
    const std::vector<double>& vertexDistances() const { return m_distance; }
    /// The vertex positions at rest, as read from the file.
    const Positions& restPoints() const { return m_rest; }

    core::Param<FilePath> m_filename{this, core::ParamSpec("filename").required().help("the visual surface: .stl (ASCII or binary), .obj or .vtp (VTK XML PolyData; needs a build with VTK), in the body's rest coordinates, relative to the scene file")};
    core::Param<double> m_maxDistance{this, core::ParamSpec("maxDistance").unit("m").min(0).help("largest distance of a vertex from the body at rest; a vertex farther out is an error (0: 5 % of the diagonal of the body's bounding box)"), 0.0};
    core::Param<std::string> m_output{this, core::ParamSpec("output").help("base name of a .vtp series of the moved surface, relative to the output folder (empty: none)")};
    core::Param<int> m_every{this, core::ParamSpec("every").min(1).help("write the .vtp series every N steps (the initial and the final state are always written)"), 1};
    core::Link<core::BaseMechanicalState> m_state{this, core::ParamSpec("state").help("the body (default: the mechanical state in the context)")};

private:
    void update();
    void write(double t, long step);
    const core::BaseMechanicalState* m_st = nullptr;
    Positions m_rest, m_displacement;
    std::vector<int> m_tet;
    std::vector<std::array<int, 4>> m_nodes;  ///< the tetrahedron's nodes per vertex
    std::vector<std::array<double, 4>> m_weights;
    std::vector<double> m_distance;
    SurfaceSeries m_series;
};

} // namespace fascia::meshio
