#pragma once
#include "DistanceGrid.h"
#include "RigidTool.h"

#include <memory>
#include <vector>

namespace fascia::contact {

/// A rigid closed triangle surface (a retractor, an ultrasound probe) read from an STL, OBJ or .vtp file,
/// its vertices in the tool's frame. It must be closed, edge-manifold and consistently oriented
/// (turned outwards when it faces in), with no degenerate triangle. Its signed distance comes from
/// a grid sampled once at init (`resolution` cells along the surface box's longest side) and, near
/// the surface, from the exact closest point of its triangles (docs/design.md, section 4.5).
class SurfaceTool : public RigidTool {
public:
    /// The most memory the distance grid may take.
    static constexpr double kMaxGridBytes = 256.0 * 1024 * 1024;

    SurfaceTool();
    ~SurfaceTool() override;
    void init() override;
    double signedDistance(const Vec3& local, Vec3& normal) const override;
    bool localBounds(double margin, Vec3& lo, Vec3& hi) const override;
    double size() const override { return m_size; }
    bool memoizeDistance() const override { return true; }
    /// The surface as read.
    bool displayMesh(double extent, Positions& points, Triangles& triangles) const override;

    /// The surface as read (outwards), its tree and its grid (null before init).
    const TriangleTree* tree() const { return m_tree.get(); }
    const DistanceGrid* grid() const { return m_grid.get(); }

    core::Param<FilePath> m_mesh{this, core::ParamSpec("mesh").required().help("the tool's closed surface: .stl (ASCII or binary), .obj or .vtp (VTK XML PolyData; needs a build with VTK), in metres in the tool's frame, relative to the scene file")};
    core::Param<int> m_resolution{this, core::ParamSpec("resolution").min(2).help("cells of the signed distance grid along the longest side of the surface's box (8 bytes a node, and 8 bytes a triangle listed in a cell near the surface: at most 256 MiB in all)"), 64};

private:
    std::unique_ptr<TriangleTree> m_tree;
    std::unique_ptr<DistanceGrid> m_grid;
    double m_size = 0;
};

} // namespace fascia::contact
