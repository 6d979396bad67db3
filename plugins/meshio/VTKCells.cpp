#include "VTKCells.h"

#include <algorithm>
#include <array>
#include <vector>

namespace fascia::meshio::detail {

std::string vtkCellName(int type) {
    switch (type) {
    case 0: return "empty cell";
    case 1: return "point";
    case 2: return "poly-point";
    case 3: return "line";
    case 4: return "polyline";
    case kVtkTriangle: return "VTK cell type 5 (vtkTriangle)";
    case 6: return "triangle strip";
    case 7: return "polygon";
    case 8: return "pixel";
    case 9: return "quadrangle";
    case kVtkTetra: return "VTK cell type 10 (vtkTetra)";
    case kVtkVoxel: return "VTK cell type 11 (vtkVoxel)";
    case kVtkHexahedron: return "VTK cell type 12 (vtkHexahedron)";
    case 13: return "prism";
    case 14: return "pyramid";
    case 21: return "3-node line";
    case 22: return "6-node triangle";
    case 23: return "8-node quadrangle";
    case 24: return "10-node tetrahedron";
    case 25: return "20-node hexahedron";
    case 26: return "15-node prism";
    case 27: return "13-node pyramid";
    case 29: return "27-node hexahedron";
    case 42: return "polyhedron";
    default: return "VTK cell type " + std::to_string(type);
    }
}

int vtkKeptCellSize(int type) {
    switch (type) {
    case kVtkTriangle: return 3;
    case kVtkTetra: return 4;
    case kVtkVoxel:
    case kVtkHexahedron: return 8;
    default: return 0;
    }
}

void addVtkCell(MeshBuilder& b, long long index, int type, const int* nodes, size_t n, int group, int line, long long byte) {
    auto& mesh = b.mesh;
    if (type == kVtkTetra && n == 4) {
        mesh.tetrahedra.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
        mesh.tetrahedronGroup.push_back(group);
        b.origin.tetNumber.push_back(index);
        if (line > 0) b.origin.tetLine.push_back(line);
        if (byte >= 0) b.origin.tetByte.push_back(byte);
    } else if ((type == kVtkHexahedron || type == kVtkVoxel) && n == 8) {
        std::array<int, 8> h;
        if (type == kVtkVoxel)  // voxels number their corners like a grid: (0,1,3,2, 4,5,7,6)
            h = {nodes[0], nodes[1], nodes[3], nodes[2], nodes[4], nodes[5], nodes[7], nodes[6]};
        else
            std::copy(nodes, nodes + 8, h.begin());
        mesh.hexahedra.push_back(h);
        mesh.hexahedronGroup.push_back(group);
        b.origin.hexNumber.push_back(index);
        if (line > 0) b.origin.hexLine.push_back(line);
        if (byte >= 0) b.origin.hexByte.push_back(byte);
    } else if (type == kVtkTriangle && n == 3) {
        mesh.triangles.push_back({nodes[0], nodes[1], nodes[2]});
        mesh.triangleGroup.push_back(group);
    } else {
        b.skip(vtkCellName(type));
    }
    if (group != 0) b.markGroup(-1, group, nodes, n);
}

void addVtkCellArray(MeshBuilder& b, const std::string& name, int components, const double* values) {
    if (components != 1 && components != 3) return;
    std::vector<double> out;
    out.reserve((b.origin.tetNumber.size() + b.origin.hexNumber.size()) * size_t(components));
    for (const auto* list : {&b.origin.tetNumber, &b.origin.hexNumber})
        for (long long c : *list)
            for (int k = 0; k < components; ++k) out.push_back(values[size_t(c) * size_t(components) + size_t(k)]);
    b.mesh.cellArrays[name] = std::move(out);
}

} // namespace fascia::meshio::detail
