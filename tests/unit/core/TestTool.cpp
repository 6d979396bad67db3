/// The rigid tool role (fascia/sim/Tool.h): Simulation::tool finds a tool by name, the pose set from
/// code is the one read back, and a tool joins the group of the body it names wherever it sits.
#include "CoreTestSupport.h"

#include "fascia/plugin/Registry.h"
#include "fascia/sim/Tool.h"

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

namespace {

/// A tool that only stores what the role asks for.
class StubTool : public BaseTool {
public:
    void setPose(const Pose& p) override { m_pose = p, m_pose.orientation.normalize(); }
    Pose pose() const override { return m_pose; }
    Vec3 force() const override { return Vec3(1, 2, 3); }
    Vec3 torque() const override { return Vec3(4, 5, 6); }
    BaseMechanicalState* body() const override { return m_body; }
    BaseMechanicalState* m_body = nullptr;
    Pose m_pose;
};

/// root (the tool) / organ (integrator, state, mass)
std::unique_ptr<Simulation> toolScene(StubTool*& tool) {
    loadTestPlugin();
    auto root = std::make_unique<Node>("root");
    root->dt.set(TimeStep{false, 0.1});
    tool = &root->add<StubTool>("probe");
    Node& organ = root->addChild("organ");
    organ.addComponent(Registry::instance().create("TestEuler")).setName("euler");
    Component& state = organ.addComponent(Registry::instance().create("TestState"));
    state.setName("state");
    tool->m_body = dynamic_cast<BaseMechanicalState*>(&state);
    auto sim = std::make_unique<Simulation>(std::move(root));
    sim->init();
    return sim;
}

} // namespace

TEST_CASE("Simulation tool finds a tool by name and its pose is the one set", "[BaseTool][Simulation]") {
    StubTool* stub = nullptr;
    auto sim = toolScene(stub);
    BaseTool& t = sim->tool("probe");
    CHECK(&t == stub);
    CHECK(&sim->tool("/root/probe") == stub);
    Pose p;
    p.position = Vec3(0.1, 0.2, 0.3);
    p.orientation = Eigen::Quaterniond(2, 0, 0, 0);  // normalised by the tool
    t.setPose(p);
    CHECK(t.pose().position == p.position);
    CHECK(t.pose().orientation.w() == 1.0);
    CHECK(t.force() == Vec3(1, 2, 3));
    CHECK(t.torque() == Vec3(4, 5, 6));
    CHECK(t.constrainedNodes().empty());
}

TEST_CASE("A tool joins the group of the body it names, not of its context", "[BaseTool][MechanicalGroup]") {
    StubTool* stub = nullptr;
    auto sim = toolScene(stub);
    REQUIRE(sim->groups().size() == 1);
    const MechanicalGroup& g = sim->groups()[0];
    CHECK(g.state == stub->body());
    REQUIRE(g.constraints.size() == 1);
    CHECK(g.constraints[0] == stub);
}

TEST_CASE("Simulation tool of a missing name or of a component that is no tool is an error", "[BaseTool][Simulation]") {
    StubTool* stub = nullptr;
    auto sim = toolScene(stub);
    auto none = errorOf([&] { sim->tool("scalpel"); });
    REQUIRE(none);
    CHECK_THAT(none->what(), Contains("no tool 'scalpel' in the scene"));
    auto other = errorOf([&] { sim->tool("state"); });
    REQUIRE(other);
    CHECK_THAT(other->what(), Contains("'state' is a TestState, not a tool"));
}
