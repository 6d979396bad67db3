// A scene with a rigid tool restarts bitwise: 200 steps straight and 100 steps, a checkpoint, a
// restore and 100 steps give the same node positions and velocities, tool force and torque and
// per-node contact forces, for a keyframed sphere with Coulomb friction (sticking, then sliding) and
// for a plane whose pose an embedding program sets (setPose: state, not a function of time).
#include "ContactTestSupport.h"

#include <unistd.h>

#include <cstring>
#include <filesystem>

using namespace contacttest;
namespace fs = std::filesystem;

namespace {

bool sameBits(const Positions& a, const Positions& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data()->data(), b.data()->data(), 24 * a.size()) == 0);
}
bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), 24) == 0; }

struct Result {
    Positions x, v, contact;
    Vec3 force, torque, position;
};
Result resultOf(Simulation& sim, const std::string& tool) {
    RigidTool& t = toolOf(sim, tool);
    return {sim.state("state").x(), sim.state("state").v(), t.contactForces(), t.force(), t.torque(), t.pose().position};
}
void checkSame(const Result& a, const Result& b) {
    CHECK(sameBits(a.x, b.x));
    CHECK(sameBits(a.v, b.v));
    CHECK(sameBits(a.contact, b.contact));
    CHECK(sameBits(a.force, b.force));
    CHECK(sameBits(a.torque, b.torque));
    CHECK(sameBits(a.position, b.position));
}

fs::path checkpointPath(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("fascia-tool-restart-" + std::to_string(getpid()));
    fs::create_directories(d);
    return d / name;
}

} // namespace

TEST_CASE("A keyframed sphere with Coulomb friction pressing a block restarts bitwise", "[SphereTool][RigidTool][Simulation]") {
    const std::string integrator = GENERATE(std::string("<SemiImplicitEuler damping=\"20\"/>"), std::string("<CentralDifference damping=\"20\"/>"));
    CAPTURE(integrator);
    // no gravity; the sphere presses 5 mm into the top, then drags 2 cm along x: the contact nodes
    // stick, then slide
    const std::string xml = blockScene(
        integrator, "    <FixedConstraint name=\"base\" group=\"zmin\"/>\n",
        "  <SphereTool name=\"ball\" body=\"@block/state\" radius=\"0.04\" keyTimes=\"0 0.05 0.15\" "
        "keyPositions=\"0.05 0.05 0.0905  0.05 0.05 0.0855  0.07 0.05 0.0855\" staticFriction=\"0.6\" kineticFriction=\"0.4\"/>\n",
        "dt=\"0.0005\" gravity=\"0 0 0\"", "8 8 2");
    const fs::path ck = checkpointPath("sphere.ckpt");
    Result straight, middle;
    {
        auto sim = Simulation::fromString(xml, "scene.xml");
        sim->run(100);
        middle = resultOf(*sim, "ball");
        sim->run(100);
        straight = resultOf(*sim, "ball");
    }
    // the state at the checkpoint and at the end has contact and friction (a tangential force
    // against the drag along x)
    CHECK(middle.force[2] > 0);
    CHECK(straight.force[0] < -0.05 * straight.force[2]);
    CHECK(straight.torque.norm() > 0);
    {
        auto first = Simulation::fromString(xml, "scene.xml");
        first->run(100);
        first->save(ck.string());
    }
    auto second = Simulation::fromString(xml, "scene.xml");
    second->restore(ck.string());
    checkSame(resultOf(*second, "ball"), middle);  // the tool's force, torque and contacts are restored
    second->run(100);
    checkSame(resultOf(*second, "ball"), straight);
}

TEST_CASE("A plane whose pose the program sets restarts at that pose, bitwise", "[PlaneTool][RigidTool][Simulation]") {
    // a floor under the block (scene pose: 1 cm below it) that the program lifts to the block at step
    // 0 and pushes 1 mm up at step 50; the restored run is given no pose: it carries the set one
    const std::string xml = blockScene("<SemiImplicitEuler damping=\"20\"/>", "",
                                       "  <PlaneTool name=\"floor\" body=\"@block/state\" position=\"0 0 -0.01\" "
                                       "staticFriction=\"0.5\"/>\n",
                                       "dt=\"0.0005\" gravity=\"0.3 0 -9.81\"");
    auto drive = [](Simulation& sim, int from, int to) {
        for (int k = from; k < to; ++k) {
            if (k == 0) toolOf(sim, "floor").setPose({Vec3(0, 0, 0), Eigen::Quaterniond::Identity()});
            if (k == 50) toolOf(sim, "floor").setPose({Vec3(0, 0, 0.001), Eigen::Quaterniond::Identity()});
            sim.step();
        }
    };
    const fs::path ck = checkpointPath("plane.ckpt");
    Result straight;
    {
        auto sim = Simulation::fromString(xml, "scene.xml");
        drive(*sim, 0, 200);
        straight = resultOf(*sim, "floor");
    }
    CHECK(straight.position[2] == 0.001);
    CHECK(straight.force[2] < 0);  // the block rests on the lifted floor
    CHECK(straight.force[0] != 0);  // and friction holds its pull
    {
        auto first = Simulation::fromString(xml, "scene.xml");
        drive(*first, 0, 100);
        first->save(ck.string());
    }
    auto second = Simulation::fromString(xml, "scene.xml");
    second->restore(ck.string());
    second->run(100);
    checkSame(resultOf(*second, "floor"), straight);
}
