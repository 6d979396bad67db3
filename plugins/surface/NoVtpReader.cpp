// The .vtp reader of a build without VTK (FASCIA_WITH_VTK=OFF): a .vtp surface is a located error
// that says how to read it, as a .vtu mesh is (plugins/meshio/NoVTKReader.cpp).
#include "VtpReader.h"

namespace fascia::surface::detail {

void readVtp(const std::string&, TriangleSurface& s) {
    core::throwInputError(core::SourceLoc{s.file, 0},
                          "this build has no VTK support: '" + s.file +
                              "' is a VTK XML PolyData (.vtp) surface; rebuild Fascia with -DFASCIA_WITH_VTK=ON (needs VTK 9), or "
                              "convert the surface to .stl or .obj");
}

} // namespace fascia::surface::detail
