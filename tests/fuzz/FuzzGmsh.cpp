// Fuzz target: the Gmsh .msh reader (ASCII 1, 2.2 and 4.1; binary files are refused), through
// readMesh. The input is the file; its size's parity picks ReadOptions::fixOrientation, so that both
// paths of the validation are fuzzed.
#include "FuzzSupport.h"
#include "MeshReaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fascia::fuzz::writeScratch("mesh.msh", data, size);
    fascia::fuzz::runExpectingLocatedErrors("gmsh", [&] {
        fascia::meshio::ReadOptions opt;
        opt.fixOrientation = size % 2 == 1;
        fascia::meshio::readMesh(path, opt);
    });
    return 0;
}
