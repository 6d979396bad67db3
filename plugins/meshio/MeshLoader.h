#pragma once
#include "MeshSource.h"

namespace fascia::meshio {

/// Reads a volume mesh; the reader is picked by the extension of `filename`: Gmsh .msh (ASCII
/// 1, 2.2, 4.1), VTK .vtk and .vtu, TetGen .node/.ele. Then scales, rotates (degrees about x,
/// then y, then z) and translates the points, in that order.
class MeshLoader : public MeshSource {
public:
    void init() override;
    int flippedElements() const { return m_flipped; }

    core::Param<FilePath> m_filename{this, core::ParamSpec("filename").required().help("mesh file (.msh, .vtk, .vtu, .node/.ele), relative to the scene file")};
    core::Param<Vec3> m_translation{this, core::ParamSpec("translation").unit("m").help("translation applied last"), Vec3::Zero()};
    core::Param<Vec3> m_rotation{this, core::ParamSpec("rotation").unit("deg").help("rotation about x, then y, then z, applied after scaling"), Vec3::Zero()};
    core::Param<double> m_scale{this, core::ParamSpec("scale").above(0).help("uniform scale applied first (e.g. 0.001 for a mesh in millimetres)"), 1.0};
    core::Param<bool> m_fixOrientation{this, core::ParamSpec("fixOrientation").help("flip inverted elements (and say how many) instead of failing"), false};

private:
    int m_flipped = 0;
};

} // namespace fascia::meshio
