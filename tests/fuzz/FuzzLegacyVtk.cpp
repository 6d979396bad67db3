// Fuzz target: the legacy VTK reader (.vtk, our own parser: ASCII and BINARY, file versions up to
// 5.1), through readMesh. The input is the file; its size's parity picks
// ReadOptions::fixOrientation, so that both paths of the validation are fuzzed.
#include "FuzzSupport.h"
#include "MeshReaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fascia::fuzz::writeScratch("mesh.vtk", data, size);
    fascia::fuzz::runExpectingLocatedErrors("legacy_vtk", [&] {
        fascia::meshio::ReadOptions opt;
        opt.fixOrientation = size % 2 == 1;
        fascia::meshio::readMesh(path, opt);
    });
    return 0;
}
