// The .vtu reader of a build without VTK (FASCIA_WITH_VTK=OFF): .vtu meshes are refused with a
// located error that says how to read them. Legacy .vtk files need no VTK (LegacyVTKReader.cpp).
#include "VTKReader.h"
#include "ReaderSupport.h"

namespace fascia::meshio::detail {

void readVtu(const std::string& path, MeshBuilder&) {
    checkReadable(path);
    fail(path, 0,
         std::string("this build has no VTK support: '") + path +
             "' is a VTK XML (.vtu) mesh; rebuild Fascia with -DFASCIA_WITH_VTK=ON (needs VTK 9), or convert the "
             "mesh to legacy VTK .vtk, Gmsh .msh or TetGen .node/.ele");
}

} // namespace fascia::meshio::detail
