// Fuzz target: the TetGen reader (.node and .ele), through readMesh. One input holds both files:
// the .node file, then the separator line "@@ele@@", then the .ele file. Without the separator the
// whole input is the .node file and there is no .ele file (a missing-file error). The .node path
// is given, except for inputs of odd size, where the .ele path is (the reader looks for the other
// one beside it).
#include "FuzzSupport.h"
#include "MeshReaders.h"

#include <string_view>

namespace {
constexpr std::string_view kSeparator = "\n@@ele@@\n";
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fascia::fuzz;
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    const size_t cut = input.find(kSeparator);
    removeScratch("mesh.ele");
    const std::string node = writeScratch("mesh.node", std::string(input.substr(0, cut)));
    std::string ele = scratchDir() + "/mesh.ele";
    if (cut != std::string_view::npos) ele = writeScratch("mesh.ele", std::string(input.substr(cut + kSeparator.size())));
    runExpectingLocatedErrors("tetgen", [&] { fascia::meshio::readMesh(size % 2 == 1 ? ele : node); });
    return 0;
}
