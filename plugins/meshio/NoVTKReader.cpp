// The VTK reader of a build without VTK (FASCIA_WITH_VTK=OFF): .vtk and .vtu meshes are refused
// with a located error that says how to read them.
#include "VTKReader.h"
#include "ReaderSupport.h"

namespace fascia::meshio::detail {

void readVtk(const std::string& path, bool xml, MeshBuilder&) {
    checkReadable(path);
    fail(path, 0,
         std::string("this build has no VTK support: '") + path + "' is a VTK " + (xml ? "XML (.vtu)" : "legacy (.vtk)") +
             " mesh; rebuild Fascia with -DFASCIA_WITH_VTK=ON (needs VTK 9), or convert the mesh to Gmsh .msh "
             "or TetGen .node/.ele");
}

} // namespace fascia::meshio::detail
