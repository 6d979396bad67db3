// Located errors for bad tool input: no body, keyframes out of order or of the wrong size, a
// negative or inconsistent friction coefficient, a shape without direction, an unknown tool name,
// and a surface tool's mesh: missing, open, non-manifold, flat, or a grid too fine.
#include "ContactTestSupport.h"
#include "SurfaceMeshes.h"

#include <algorithm>
#include <iterator>

using namespace contacttest;
using Catch::Matchers::Contains;

namespace {
/// A tool at the root next to a block (the tool's attributes on line 2 of the scene).
std::string withTool(const std::string& tool) {
    return blockScene("<SemiImplicitEuler/>", "", "  " + tool + "\n", "dt=\"0.001\"");
}
} // namespace

TEST_CASE("A tool with no body to touch is a located error", "[RigidTool]") {
    const std::string e = errorOf("<Node name=\"root\" dt=\"0.001\">\n  <SphereTool name=\"ball\" radius=\"0.01\"/>\n</Node>\n");
    CHECK_THAT(e, Contains("scene.xml:2: error: SphereTool 'ball': no body to touch"));
    CHECK_THAT(e, Contains("body=\"@../liver/state\""));
}

TEST_CASE("Keyframes out of order are a located error naming the keys", "[RigidTool][ToolMotion]") {
    const std::string e = errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" keyTimes=\"0 2 1\" keyPositions=\"0 0 1 0 0 2 0 0 3\"/>"));
    CHECK_THAT(e, Contains("scene.xml:2: error: PlaneTool 'plate': keyframe times must increase: key 2 (t = 1 s) does not come after key 1 (t = 2 s)"));
    const std::string same = errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" keyTimes=\"0 0\" keyPositions=\"0 0 1 0 0 2\"/>"));
    CHECK_THAT(same, Contains("key 1 (t = 0 s) does not come after key 0 (t = 0 s)"));
}

TEST_CASE("Keyframe lists of the wrong length are located errors", "[RigidTool][ToolMotion]") {
    CHECK_THAT(errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" keyTimes=\"0 1\" keyPositions=\"0 0 1\"/>")),
               Contains("scene.xml:2: error: PlaneTool 'plate': has 3 numbers for 2 key times: give 3 (x y z) per key"));
    CHECK_THAT(errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" keyTimes=\"0 1\" keyPositions=\"0 0 1 0 0 2\" keyOrientations=\"1 0 0 0\"/>")),
               Contains("has 4 numbers for 2 key times: give 4 (w x y z) per key"));
    CHECK_THAT(errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" keyPositions=\"0 0 1\"/>")),
               Contains("keyframes need keyTimes"));
    CHECK_THAT(errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" keyTimes=\"0\" keyPositions=\"0 0 1\" positionCurve=\"ramp 1\"/>")),
               Contains("a tool moves by keyframes or by positionCurve, not both"));
}

TEST_CASE("A negative friction coefficient is a located error", "[RigidTool]") {
    CHECK_THAT(errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" staticFriction=\"-0.1\"/>")),
               Contains("scene.xml:2: error: PlaneTool 'plate': staticFriction"));
    CHECK_THAT(errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" kineticFriction=\"-0.1\"/>")),
               Contains("scene.xml:2: error: PlaneTool 'plate': kineticFriction"));
    CHECK_THAT(errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" staticFriction=\"0.2\" kineticFriction=\"0.3\"/>")),
               Contains("kineticFriction = 0.3 is above staticFriction = 0.2"));
}

TEST_CASE("A shape without a direction or size is a located error", "[PlaneTool][CapsuleTool][SphereTool]") {
    CHECK_THAT(errorOf(withTool("<PlaneTool name=\"plate\" body=\"@block/state\" normal=\"0 0 0\"/>")),
               Contains("scene.xml:2: error: PlaneTool 'plate': the normal has no direction"));
    CHECK_THAT(errorOf(withTool("<CapsuleTool name=\"probe\" body=\"@block/state\" radius=\"0.01\" length=\"0.1\" axis=\"0 0 0\"/>")),
               Contains("CapsuleTool 'probe': the axis has no direction"));
    CHECK_THAT(errorOf(withTool("<SphereTool name=\"ball\" body=\"@block/state\" radius=\"0\"/>")),
               Contains("scene.xml:2: error: SphereTool 'ball': radius"));
    CHECK_THAT(errorOf(withTool("<SphereTool name=\"ball\" body=\"@block/state\" radius=\"0.1\" orientation=\"0 0 0 0\"/>")),
               Contains("SphereTool 'ball': the quaternion 0 0 0 0 has no direction"));
}

TEST_CASE("A surface tool's bad mesh or resolution is a located error", "[SurfaceTool]") {
    using namespace surfacetest;
    TempDir dir("errors");
    const Mesh box = Voxels::box(Vec3(0, 0, 0), Vec3(0.02, 0.02, 0.01), 1, 1, 1).surface();  // 8 vertices, 12 triangles
    auto tool = [&](const std::string& attrs) { return withTool("<SurfaceTool name=\"probe\" body=\"@block/state\" " + attrs + "/>"); };
    const std::string good = writeObj(dir.file("box.obj"), box);
    CHECK(errorOf(tool("mesh=\"" + good + "\"")).empty());
    CHECK_THAT(errorOf(tool("mesh=\"" + dir.file("nope.obj") + "\"")),
               Contains("scene.xml:2: error: SurfaceTool 'probe': mesh file '" + dir.file("nope.obj") + "' does not exist"));
    CHECK_THAT(errorOf(tool("")), Contains("scene.xml:2: error: SurfaceTool 'probe'"));
    // the last triangle left out: an edge of one of its neighbours has no neighbour across it
    const std::string e = errorOf(tool("mesh=\"" + writeObj(dir.file("open.obj"), box, 1) + "\""));
    CHECK_THAT(e, Contains("open.obj:"));
    CHECK_THAT(e, Contains(": error: the edge between vertices"));
    CHECK_THAT(e, Contains("has no neighbour across it: the surface is open"));
    CHECK_THAT(e, Contains("SurfaceTool 'probe' needs a closed, edge-manifold, consistently oriented surface"));
    CHECK_THAT(e, Contains("read by SurfaceTool 'probe' at scene.xml:2"));
    // a second closed box sharing one edge of the first (y = z = 0): four triangles on that edge
    Mesh both = box;
    const Mesh twin = Voxels::box(Vec3(0, -0.02, -0.01), Vec3(0.02, 0, 0), 1, 1, 1).surface();
    std::vector<int> id;
    for (const Vec3& p : twin.points) {
        const auto at = std::find(box.points.begin(), box.points.end(), p);
        id.push_back(at != box.points.end() ? int(at - box.points.begin()) : int(both.points.size()));
        if (at == box.points.end()) both.points.push_back(p);
    }
    for (const auto& t : twin.triangles) both.triangles.push_back({id[size_t(t[0])], id[size_t(t[1])], id[size_t(t[2])]});
    REQUIRE(both.points.size() == 14);
    CHECK_THAT(errorOf(tool("mesh=\"" + writeObj(dir.file("twin.obj"), both) + "\"")),
               Contains("is shared by three or more triangles: the surface is not edge-manifold"));
    // two triangles (lines 24 and 25) on three vertices of a line: closed, but without a normal
    const std::string flat = writeObj(dir.file("flat.obj"), box, 0, "v 0 0 0.5\nv 0 0 1\nv 0 0 2\nf 9 10 11\nf 9 11 10\n");
    CHECK_THAT(errorOf(tool("mesh=\"" + flat + "\"")), Contains("flat.obj:24: error: triangle 13 has no area"));
    // resolutions
    CHECK_THAT(errorOf(tool("mesh=\"" + good + "\" resolution=\"1\"")), Contains("scene.xml:2: error: SurfaceTool 'probe': resolution"));
    CHECK_THAT(errorOf(tool("mesh=\"" + good + "\" resolution=\"ten\"")), Contains("scene.xml:2: error: SurfaceTool 'probe': resolution"));
    CHECK_THAT(errorOf(tool("mesh=\"" + good + "\" resolution=\"1000\"")),
               Contains("scene.xml:2: error: SurfaceTool 'probe': resolution = 1000: the signed distance grid (1007 x 1007 x 507 nodes, "));
    CHECK_THAT(errorOf(tool("mesh=\"" + good + "\" resolution=\"1000\"")),
               Contains(" MiB) and the triangle lists of its cells near the surface take more than the limit of 256 MiB"));
}

TEST_CASE("A surface tool's .vtp mesh gets the closed-surface checks of an .obj or .stl one, at the byte of a triangle", "[SurfaceTool]") {
    using namespace surfacetest;
    TempDir dir("vtp-errors");
    const Mesh box = Voxels::box(Vec3(0, 0, 0), Vec3(0.02, 0.02, 0.01), 1, 1, 1).surface();  // 8 vertices, 12 triangles
    auto tool = [&](const std::string& file) { return withTool("<SurfaceTool name=\"probe\" body=\"@block/state\" mesh=\"" + file + "\"/>"); };
#if FASCIA_CONTACT_TEST_WITH_VTK
    CHECK(errorOf(tool(writeVtp(dir.file("box.vtp"), box))).empty());
    // the last triangle left out: open, located at the first point of the triangle named
    const std::string open = writeVtp(dir.file("open.vtp"), box, 1);
    const std::string e = errorOf(tool(open));
    CHECK_THAT(e, Catch::StartsWith(open + ": byte "));
    CHECK_THAT(e, Contains("has no neighbour across it: the surface is open") &&
                      Contains("SurfaceTool 'probe' needs a closed, edge-manifold, consistently oriented surface") &&
                      Contains("read by SurfaceTool 'probe' at scene.xml:2"));
    const size_t byte = std::stoul(e.substr(open.size() + 7)), tri = std::stoul(e.substr(e.find("of triangle ") + 12)) - 1;
    std::ifstream in(open);
    const std::string text(std::istreambuf_iterator<char>(in), {});
    const auto& t = box.triangles[tri];
    CHECK(text.substr(byte, text.find('\n', byte) - byte) == std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]));
    // one triangle turned over
    Mesh turned = box;
    std::swap(turned.triangles[4][1], turned.triangles[4][2]);
    CHECK_THAT(errorOf(tool(writeVtp(dir.file("turned.vtp"), turned))),
               Contains("turned.vtp: byte ") && Contains("the triangles are not consistently oriented"));
#else
    CHECK_THAT(errorOf(tool(writeVtp(dir.file("box.vtp"), box))),
               Contains("box.vtp: error: this build has no VTK support") && Contains("read by SurfaceTool 'probe' at scene.xml:2"));
#endif
}
