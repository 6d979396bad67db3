#pragma once
/// Value types shared by every plugin: links between components carry these.
#include "fascia/base/Abi.h"  // first: it fixes Eigen's alignment for every user of the library

#include <Eigen/Dense>  // Core alone declares cross() and determinant() without defining them
#include <array>
#include <map>
#include <string>
#include <vector>

namespace fascia {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

using Positions = std::vector<Vec3>;            ///< one point per node, metres
using Tetrahedra = std::vector<std::array<int, 4>>;  ///< 0-based node indices
using Hexahedra = std::vector<std::array<int, 8>>;   ///< 0-based, VTK/Gmsh node order
using Triangles = std::vector<std::array<int, 3>>;   ///< 0-based node indices
using IndexList = std::vector<int>;
using NumberList = std::vector<double>;

/// A file path as written in the scene; resolved() is relative to the scene file's folder.
struct FilePath {
    std::string written;   ///< as in the scene
    std::string resolved;  ///< absolute or relative to the working directory
};

/// dt: a number of seconds, or "auto" (the smallest stable step of the force fields).
struct TimeStep {
    bool automatic = false;
    double value = 0.0;
};

/// A mesh as read from a file, before it becomes a mechanical state.
struct MeshData {
    Positions points;
    Tetrahedra tetrahedra;
    Hexahedra hexahedra;
    Triangles triangles;                 ///< boundary triangles where the file has them
    std::vector<int> tetrahedronGroup;   ///< physical group tag per tetrahedron (0: none)
    std::vector<int> hexahedronGroup;    ///< physical group tag per hexahedron (0: none)
    std::vector<int> triangleGroup;      ///< physical group tag per triangle (0: none)
    std::map<int, std::string> groupNames;             ///< tag -> name where the file names it
    std::map<std::string, IndexList> nodeGroups;       ///< name -> sorted unique node indices
    std::map<std::string, std::vector<double>> cellArrays; ///< per-cell data arrays (e.g. fibre directions, 3 per cell)
};

} // namespace fascia
