// Fuzz target: the triangle surface reader (STL ASCII and binary, Wavefront OBJ), through
// readSurface, then the closed-surface check (requireClosedSurface) on what it accepts. The input is
// the file; its size's parity picks the extension: even sizes are read as .stl (a binary STL file,
// 84 + 50 n bytes, is always even), odd ones as .obj.
#include "FuzzSupport.h"
#include "fascia/surface/TriangleSurface.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fascia::fuzz::writeScratch(size % 2 == 1 ? "surface.obj" : "surface.stl", data, size);
    fascia::fuzz::runExpectingLocatedErrors("surface", [&] {
        fascia::surface::TriangleSurface s = fascia::surface::readSurface(path);
        fascia::surface::requireClosedSurface(s, "the fuzz target");
    });
    return 0;
}
