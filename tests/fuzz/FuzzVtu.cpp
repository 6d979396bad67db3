// Fuzz target: the .vtu path, through the header check (checkVtuHeaders, which needs no VTK) and
// then readMesh (VTK's XML reader after the same check, in a build with VTK; a located error
// without). The input is the file; its size's parity picks ReadOptions::fixOrientation.
#include "FuzzSupport.h"
#include "MeshReaders.h"
#include "VTUHeaderCheck.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fascia::fuzz::writeScratch("mesh.vtu", data, size);
    fascia::fuzz::runExpectingLocatedErrors("vtu", [&] {
        fascia::meshio::detail::checkVtuHeaders(path);
        fascia::meshio::ReadOptions opt;
        opt.fixOrientation = size % 2 == 1;
        fascia::meshio::readMesh(path, opt);
    });
    return 0;
}
