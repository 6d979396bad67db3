// Fuzz target: the scene loader from text: parse (XML, includes), build (components, parameters,
// links; <RequiredPlugin> loads plugins) and, where cheap, init. The built-in plugins are loaded
// once. The scene's folder is the scratch folder, which holds a small tetrahedral cube, cube.msh
// (the seeds' MeshLoader filenames name it), so that init reaches the mechanics. Init is skipped for
// scenes whose GridMesh resolution asks for more than kMaxInitCells cells: a large grid is valid
// input, only slow.
#include "FuzzSupport.h"

#include "fascia/plugin/PluginManager.h"
#include "fascia/scene/SceneLoader.h"
#include "fascia/sim/Simulation.h"

#include <sstream>

namespace {

constexpr double kMaxInitCells = 4096;

/// The unit cube as 5 tetrahedra, Gmsh 2.2, with the physical groups "tissue" (volume) and
/// "bottom" (its z = 0 face).
constexpr const char* kCubeMesh = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
2 2 "bottom"
3 1 "tissue"
$EndPhysicalNames
$Nodes
8
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0 0 1
6 1 0 1
7 1 1 1
8 0 1 1
$EndNodes
$Elements
7
1 2 2 2 5 1 4 2
2 2 2 2 5 2 4 3
3 4 2 1 1 1 2 4 5
4 4 2 1 1 3 4 2 7
5 4 2 1 1 6 5 7 2
6 4 2 1 1 8 7 5 4
7 4 2 1 1 2 4 5 7
$EndElements
)";

/// Cells asked for by every "resolution" attribute of the scene (their product, summed).
double gridCells(const fascia::core::ElementSpec& e) {
    double cells = 0;
    for (const auto& [name, value] : e.attributes) {
        if (name != "resolution") continue;
        std::istringstream in(value);
        double product = 1, r = 0;
        while (in >> r) product *= r < 1 ? 1 : r;
        cells += product;
    }
    for (const auto& child : e.children) cells += gridCells(child);
    return cells;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fascia;
    static const bool ready = [] {
        core::PluginManager::instance().loadDefaultPlugins();
        fuzz::writeScratch("cube.msh", kCubeMesh);
        return true;
    }();
    (void)ready;
    const std::string xml(reinterpret_cast<const char*>(data), size);
    fuzz::runExpectingLocatedErrors("scene", [&] {
        const core::ElementSpec spec = core::parseSceneString(xml, "fuzz.xml", fuzz::scratchDir());
        auto root = core::buildScene(spec);
        if (!(gridCells(spec) <= kMaxInitCells)) return;
        core::Simulation sim(std::move(root));
        core::LoadOptions options;
        options.outputDir = fuzz::scratchDir() + "/out";
        sim.configure(options);
        sim.init();
    });
    return 0;
}
