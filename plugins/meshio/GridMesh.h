#pragma once
#include "MeshSource.h"

namespace fascia::meshio {

/// A box split into hexahedra or tetrahedra (5 or 6 per cell), for tests and benchmarks.
/// Node groups: xmin, xmax, ymin, ymax, zmin, zmax (the six faces).
class GridMesh : public MeshSource {
public:
    /// How makeGrid numbers nodes and cells (for --describe).
    static constexpr const char* kNumbering =
        "node numbering: with resolution \"nx ny nz\", node (i, j, k), 0 <= i <= nx, 0 <= j <= ny, 0 <= k <= nz, at "
        "min + (i/nx, j/ny, k/nz) (max - min), has index i + (nx + 1) (j + (ny + 1) k): x fastest, then y, then z; node 0 "
        "is at min, node (nx + 1)(ny + 1)(nz + 1) - 1 at max. Cells (i, j, k) in the same order; a hexahedron's corners in "
        "VTK order (i,j,k) (i+1,j,k) (i+1,j+1,k) (i,j+1,k), then the same at k+1; tetrahedra6: six per cell around the "
        "diagonal from corner 0 to corner 6; tetrahedra5: five per cell, the split alternating with the parity of i + j + k. "
        "Node groups xmin xmax ymin ymax zmin zmax: the nodes of each face, in index order";
    void init() override;

    core::Param<Vec3> m_min{this, core::ParamSpec("min").unit("m").help("lower corner of the box"), Vec3(0, 0, 0)};
    core::Param<Vec3> m_max{this, core::ParamSpec("max").unit("m").help("upper corner of the box"), Vec3(1, 1, 1)};
    core::Param<IndexList> m_resolution{this, core::ParamSpec("resolution").count(3).min(1).help("number of cells along x, y and z"), IndexList{4, 4, 4}};
    core::Param<std::string> m_element{this, core::ParamSpec("element").choices({"tetrahedra6", "tetrahedra5", "hexahedra"}).help("cell split: 6 tetrahedra around the main diagonal, 5 tetrahedra (alternating, conforming), or one hexahedron"), "tetrahedra6"};
};

/// The grid itself, for code that wants one without a scene (benchmarks, tests).
MeshData makeGrid(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz, const std::string& element);

} // namespace fascia::meshio
