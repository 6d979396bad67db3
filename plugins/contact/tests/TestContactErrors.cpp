// Located errors for bad tool input: no body, keyframes out of order or of the wrong size, a
// negative or inconsistent friction coefficient, a shape without direction, an unknown tool name.
#include "ContactTestSupport.h"

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
