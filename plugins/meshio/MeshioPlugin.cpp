// fascia.meshio: meshes in (files, generated grids, regions), results out.
#include "fascia/plugin/Plugin.h"

#include "BarycentricSurfaceMapping.h"
#include "BoxROI.h"
#include "GridMesh.h"
#include "InlineMesh.h"
#include "MeshLoader.h"
#include "Monitor.h"
#if FASCIA_MESHIO_WITH_VTK
#include "VTKExporter.h"
#endif

using namespace fascia::meshio;

static void registerMeshio(fascia::core::Registry& r) {
    r.add<MeshLoader>("MeshLoader", "reads a volume mesh: Gmsh .msh (1, 2.2, 4.1), VTK .vtk/.vtu, TetGen .node/.ele");
    r.add<GridMesh>("GridMesh", std::string("a box split into hexahedra or tetrahedra, with its six faces as node groups\n") +
                                    GridMesh::kNumbering);
    r.add<InlineMesh>("InlineMesh", "a volume mesh given in the scene itself (points, tetrahedra, hexahedra, node groups): what Python's fascia.Mesh builds");
    r.add<BoxROI>("BoxROI", "the nodes and elements inside a box, as index lists");
#if FASCIA_MESHIO_WITH_VTK  // a build without VTK (FASCIA_WITH_VTK=OFF) has no VTKExporter
    r.add<VTKExporter>("VTKExporter", "ParaView time series (.pvd + .vtu): displacement, velocity, force, cell data");
#endif
    r.add<BarycentricSurfaceMapping>("BarycentricSurfaceMapping", "a finer visual surface (.stl/.obj/.vtp) moved with the tetrahedra of a body (and written as .vtp)");
    r.add<Monitor>("Monitor", "CSV of node positions/displacements/velocities, reaction forces and element quantities");
}

FASCIA_PLUGIN("fascia.meshio", "0.1.0", "mesh loaders, generated meshes, regions, exporters and monitors", registerMeshio)
