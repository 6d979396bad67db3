// Rigid tools touching a block: the weight a plane carries with every integrator and force field,
// the pose from keyframes and from the API, the torque of a frictionless sphere, Coulomb friction,
// energy, and determinism over thread counts.
#include "ContactTestSupport.h"

#include <omp.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <unistd.h>
#include <sstream>

using namespace contacttest;
using fascia::core::Pose;

namespace {

/// A block on a frictionless floor (PlaneTool at z = 0) under gravity g = 1 m/s^2, on symmetry
/// rollers at xmin and ymin (so that a static solver has no free rigid motion).
std::string floorScene(const std::string& integrator, const std::string& ff, const std::string& element,
                       const std::string& rootAttrs) {
    return blockScene(integrator,
                      "    <FixedConstraint name=\"symX\" group=\"xmin\" directions=\"1 0 0\"/>\n"
                      "    <FixedConstraint name=\"symY\" group=\"ymin\" directions=\"0 1 0\"/>\n",
                      "  <PlaneTool name=\"floor\" body=\"@block/state\" normal=\"0 0 1\"/>\n", rootAttrs, "4 4 2", ff, element);
}

} // namespace

TEST_CASE("A frictionless floor carries the block's weight with every integrator and force field", "[PlaneTool][RigidTool]") {
    struct Case { const char* integrator; const char* ff; const char* element; double tol; };
    const Case c = GENERATE(Case{"<DynamicRelaxation name=\"dr\"/>", "HEMLForceField", "tetrahedra6", 1e-6},
                            Case{"<DynamicRelaxation name=\"dr\"/>", "TLEDForceField", "hexahedra", 1e-6},
                            Case{"<SemiImplicitEuler damping=\"60\"/>", "TLEDForceField", "tetrahedra6", 1e-4},
                            Case{"<CentralDifference damping=\"60\"/>", "HEMLForceField", "tetrahedra5", 1e-4},
                            Case{"<ExplicitEuler damping=\"60\"/>", "TLEDForceField", "hexahedra", 1e-4});
    CAPTURE(c.integrator, c.ff, c.element);
    const bool statics = std::string(c.integrator).find("Dynamic") != std::string::npos;
    auto sim = Simulation::fromString(floorScene(c.integrator, c.ff, c.element,
                                                 statics ? "dt=\"1\" gravity=\"0 0 -1\"" : "dt=\"auto\" gravity=\"0 0 -1\""),
                                      "scene.xml");
    if (statics)
        sim->run(1);
    else
        sim->runUntil(1.5);
    RigidTool& floor = toolOf(*sim, "floor");
    const double weight = 1000 * 0.1 * 0.1 * 0.05 * 1.0;  // rho V g
    CHECK(floor.force()[2] == Approx(-weight).epsilon(c.tol));
    CHECK(std::abs(floor.force()[0]) < 1e-12);
    CHECK(std::abs(floor.force()[1]) < 1e-12);
    CHECK(floor.contactCount() == 25);  // the bottom face's 5 x 5 nodes
    double lowest = 1;
    for (const Vec3& x : sim->state("state").x()) lowest = std::min(lowest, x[2]);
    CHECK(lowest > -1e-9);
    // the contact forces are the nodes' reactions, and the tool's force is minus their sum
    CHECK((sum(floor.contactForces()) + floor.force()).norm() < 1e-12 * weight);
    CHECK(sim->state("state").reaction()[24] == floor.contactForces()[24]);  // (0.1, 0.1, 0): on no roller
    CHECK(floor.contactForces()[24][2] > 0);
    if (statics) {  // the solution is where the forces were last evaluated: the torque about the origin
        Vec3 t = Vec3::Zero();
        const Positions& x = sim->state("state").x();
        for (size_t i = 0; i < x.size(); ++i) t -= x[i].cross(floor.contactForces()[i]);
        CHECK((t - floor.torque()).norm() < 1e-12 * t.norm());
        CHECK(t.norm() > 0.01 * weight * 0.05);  // the weight acts at the block's centre, off the origin
    }
}

TEST_CASE("A frictionless sphere's force points through its centre and its torque about it is zero", "[SphereTool][RigidTool]") {
    // a sphere pushed off-centre into the block's top by keyframes, a damped dynamic run
    auto sim = Simulation::fromString(
        blockScene("<SemiImplicitEuler damping=\"60\"/>", "    <FixedConstraint name=\"base\" group=\"zmin\"/>\n",
                   "  <SphereTool name=\"ball\" body=\"@block/state\" radius=\"0.03\" keyTimes=\"0 0.5\" "
                   "keyPositions=\"0.04 0.06 0.085  0.04 0.06 0.075\"/>\n",
                   "dt=\"auto\"", "6 6 3"),
        "scene.xml");
    sim->runUntil(0.8);
    RigidTool& ball = toolOf(*sim, "ball");
    CHECK(ball.pose().position.isApprox(Vec3(0.04, 0.06, 0.075), 1e-15));
    REQUIRE(ball.contactCount() > 3);
    CHECK(ball.force()[2] > 0);  // the block pushes the ball up
    CHECK(ball.torque().norm() < 1e-12 * ball.force().norm() * 0.03);
    // nodes touching the sphere are on its surface, none inside
    for (const Vec3& p : sim->state("state").x()) CHECK((p - ball.pose().position).norm() > 0.03 * (1 - 1e-9));
}

TEST_CASE("Keyframes interpolate positions linearly and orientations by slerp", "[CapsuleTool][RigidTool]") {
    auto sim = Simulation::fromString(
        blockScene("<SemiImplicitEuler/>", "", "  <CapsuleTool name=\"probe\" body=\"@block/state\" radius=\"0.005\" length=\"0.1\" "
                                                "keyTimes=\"0.001 0.003\" keyPositions=\"0 0 1  0 0.2 1\" "
                                                "keyOrientations=\"1 0 0 0  0 0 0 1\"/>\n",
                   "dt=\"0.001\""),
        "scene.xml");
    RigidTool& probe = toolOf(*sim, "probe");
    CHECK(probe.pose().position == Vec3(0, 0, 1));  // before the first key: the first
    sim->run(2);
    CHECK(probe.pose().position.isApprox(Vec3(0, 0.1, 1), 1e-12));
    const double half = std::sqrt(0.5);  // halfway between no rotation and pi about z
    CHECK(std::abs(probe.pose().orientation.w() - half) < 1e-12);
    CHECK(std::abs(probe.pose().orientation.z() - half) < 1e-12);
    sim->run(3);
    CHECK(probe.pose().position == Vec3(0, 0.2, 1));  // after the last key: the last
}

TEST_CASE("A load curve moves a tool along its displacement", "[SphereTool][RigidTool]") {
    auto sim = Simulation::fromString(
        blockScene("<SemiImplicitEuler/>", "", "  <SphereTool name=\"ball\" body=\"@block/state\" radius=\"0.01\" position=\"0 0 1\" "
                                                "displacement=\"0 0.2 -0.4\" positionCurve=\"ramp 0.004\"/>\n",
                   "dt=\"0.001\""),
        "scene.xml");
    RigidTool& ball = toolOf(*sim, "ball");
    sim->run(1);
    CHECK(ball.pose().position.isApprox(Vec3(0, 0.05, 0.9), 1e-12));
    sim->run(5);  // the ramp held at 1 after t = 0.004 s
    CHECK(ball.pose().position.isApprox(Vec3(0, 0.2, 0.6), 1e-12));
}

TEST_CASE("setPose moves a tool at the next step and replaces its keyframes", "[PlaneTool][RigidTool]") {
    auto sim = Simulation::fromString(
        blockScene("<SemiImplicitEuler/>", "", "  <PlaneTool name=\"plate\" body=\"@block/state\" normal=\"0 0 -1\" keyTimes=\"0 1\" "
                                                "keyPositions=\"0 0 1  0 0 2\"/>\n",
                   "dt=\"0.001\""),
        "scene.xml");
    auto& plate = sim->tool("plate");
    Pose p;
    p.position = Vec3(0, 0, 0.049);  // 1 mm into the 50 mm block
    plate.setPose(p);
    CHECK(plate.pose().position == p.position);  // before any step: at once
    const auto& x = sim->state("state").x();
    const double top = x.back()[2];
    CHECK(top == 0.05);
    sim->step();
    CHECK(plate.pose().position == p.position);
    CHECK(x.back()[2] == Approx(0.049).epsilon(1e-12));  // the top nodes pushed onto the plate
    p.position = Vec3(0, 0, 0.048);
    plate.setPose(p);
    CHECK(plate.pose().position[2] == 0.049);  // between steps: from the next step on
    sim->step();
    CHECK(plate.pose().position[2] == 0.048);
    CHECK(x.back()[2] == Approx(0.048).epsilon(1e-12));
}

TEST_CASE("Tool force and torque columns of the Monitor are the tool's force and torque", "[RigidTool][Monitor]") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("fascia_contact_monitor_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    fascia::core::LoadOptions opt;
    opt.outputDir = dir.string();
    auto sim = Simulation::fromString(
        blockScene("<SemiImplicitEuler damping=\"60\"/>", "    <FixedConstraint name=\"base\" group=\"zmin\"/>\n",
                   "  <SphereTool name=\"ball\" body=\"@block/state\" radius=\"0.03\" keyTimes=\"0 1\" keyPositions=\"0.05 0.05 0.079  0.05 0.05 0.069\"/>\n"
                   "  <Monitor name=\"feel\" tool=\"@ball\" displacements=\"false\"/>\n"
                   "  <Monitor name=\"where\" tool=\"@ball\" toolPosition=\"true\" displacements=\"false\"/>\n"),
        "scene.xml", ".", opt);
    sim->run(5);
    sim->finish();
    std::ifstream in(dir / "feel.csv");
    std::string header, row, last;
    std::getline(in, header);
    CHECK(header == "time [s],ball_force_x [N],ball_force_y [N],ball_force_z [N],ball_torque_x [N m],ball_torque_y [N m],ball_torque_z [N m]");
    while (std::getline(in, row)) last = row;
    std::istringstream ls(last);
    std::vector<double> v;
    for (std::string cell; std::getline(ls, cell, ',');) v.push_back(std::stod(cell));
    REQUIRE(v.size() == 7);
    const RigidTool& ball = toolOf(*sim, "ball");
    CHECK(ball.force()[2] > 0);
    for (int a = 0; a < 3; ++a) {
        CHECK(v[1 + a] == Approx(ball.force()[a]).epsilon(1e-11).margin(1e-300));
        CHECK(v[4 + a] == Approx(ball.torque()[a]).epsilon(1e-11).margin(1e-15));
    }
    // toolPosition: the pose at each row's time (keyframes: z = 0.079 - 0.01 t), before the force columns
    std::ifstream where(dir / "where.csv");
    std::getline(where, header);
    CHECK(header == "time [s],ball_x [m],ball_y [m],ball_z [m],ball_force_x [N],ball_force_y [N],ball_force_z [N],"
                    "ball_torque_x [N m],ball_torque_y [N m],ball_torque_z [N m]");
    int rows = 0;
    for (std::vector<double> w; std::getline(where, row); ++rows) {
        std::istringstream ws(row);
        w.clear();
        for (std::string cell; std::getline(ws, cell, ',');) w.push_back(std::stod(cell));
        REQUIRE(w.size() == 10);
        CHECK(w[1] == Approx(0.05).epsilon(1e-12));
        CHECK(w[3] == Approx(0.079 - 0.01 * w[0]).epsilon(1e-12));
        if (rows == 5) {
            CHECK(w[3] == Approx(ball.pose().position[2]).epsilon(1e-12));
            CHECK(w[6] == Approx(ball.force()[2]).epsilon(1e-11));
        }
    }
    CHECK(rows == 6);
    fs::remove_all(dir);
}

TEST_CASE("Every shape takes its pose from position and orientation, a load curve or keyframes", "[PlaneTool][SphereTool][CapsuleTool][SurfaceTool][ToolMotion]") {
    const std::string shape = GENERATE(std::string("PlaneTool normal=\"0 0 -1\""), std::string("SphereTool radius=\"0.01\""),
                                       std::string("CapsuleTool radius=\"0.01\" length=\"0.05\""),
                                       std::string("SurfaceTool mesh=\"" FASCIA_SOURCE_DIR "/scenes/meshes/probe.obj\" resolution=\"8\""));
    CAPTURE(shape);
    const double h = std::sqrt(0.5);  // a quarter turn about z: w = z = sqrt(1/2)
    auto run = [&](const std::string& pose, int steps) {
        auto sim = Simulation::fromString(
            blockScene("<SemiImplicitEuler/>", "", "  <" + shape + " name=\"tool\" body=\"@block/state\" staticFriction=\"0.3\" kineticFriction=\"0.2\" " + pose + "/>\n",
                       "dt=\"0.001\""),
            "scene.xml");
        sim->run(steps);
        return sim->tool("tool").pose();
    };
    const auto fixed = run("position=\"0 0 2\" orientation=\"2 0 0 2\"", 1);
    CHECK(fixed.position == Vec3(0, 0, 2));
    CHECK(std::abs(fixed.orientation.w() - h) < 1e-15);
    CHECK(std::abs(fixed.orientation.z() - h) < 1e-15);
    const auto curve = run("position=\"0 0 2\" displacement=\"0 0 1\" positionCurve=\"ramp 0.004\"", 2);
    CHECK(curve.position.isApprox(Vec3(0, 0, 2.5), 1e-12));
    const auto keyed = run("keyTimes=\"0 0.002\" keyPositions=\"0 0 2  0 0 3\" keyOrientations=\"1 0 0 0  0 0 0 1\"", 1);
    CHECK(keyed.position.isApprox(Vec3(0, 0, 2.5), 1e-12));
    CHECK(std::abs(keyed.orientation.w() - h) < 1e-12);
}

TEST_CASE("Every shape's display mesh lies on its surface, is closed and faces outwards", "[PlaneTool][SphereTool][CapsuleTool][SurfaceTool]") {
    struct Case { std::string shape; double volume; };  // volume: the shape's own (0: a plane, not closed)
    const double r = 0.01, L = 0.05;
    const Case c = GENERATE_COPY(Case{"PlaneTool normal=\"1 2 2\"", 0.0}, Case{"SphereTool radius=\"0.01\"", 4.0 / 3 * M_PI * r * r * r},
                                 Case{"CapsuleTool radius=\"0.01\" length=\"0.05\" axis=\"1 1 0\"", 4.0 / 3 * M_PI * r * r * r + M_PI * r * r * L},
                                 Case{"SurfaceTool mesh=\"" FASCIA_SOURCE_DIR "/scenes/meshes/probe.obj\" resolution=\"8\"", -1.0});
    CAPTURE(c.shape);
    auto sim = Simulation::fromString(
        blockScene("<SemiImplicitEuler/>", "", "  <" + c.shape + " name=\"tool\" body=\"@block/state\" position=\"0 0 2\"/>\n", "dt=\"0.001\""),
        "scene.xml");
    auto& tool = dynamic_cast<fascia::contact::RigidTool&>(sim->tool("tool"));
    fascia::Positions p;
    fascia::Triangles t;
    REQUIRE(tool.displayMesh(0.2, p, t));
    REQUIRE(!t.empty());
    const double size = std::max(tool.size(), 0.2);
    std::map<std::pair<int, int>, int> edges;  // directed edge -> count
    double volume = 0;
    for (auto& tri : t) {
        for (int k = 0; k < 3; ++k) ++edges[{tri[k], tri[(k + 1) % 3]}];
        const Vec3 n = (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]);
        const Vec3 centroid = (p[tri[0]] + p[tri[1]] + p[tri[2]]) / 3;
        Vec3 outward;
        tool.signedDistance(centroid, outward);
        CHECK(n.dot(outward) > 0);  // every triangle turned outwards
        volume += p[tri[0]].dot(p[tri[1]].cross(p[tri[2]])) / 6;
    }
    for (auto& x : p) {
        Vec3 n;
        CHECK(std::abs(tool.signedDistance(x, n)) < 1e-9 * size);  // the vertices are on the surface
    }
    if (c.volume == 0) return;  // a plane's square has a border
    for (auto& [e, count] : edges) {  // closed and consistently oriented: each edge once each way
        CHECK(count == 1);
        CHECK(edges.count({e.second, e.first}) == 1);
    }
    if (c.volume > 0) CHECK(std::abs(volume / c.volume - 1) < 0.03);  // the facets' volume, a little under the shape's
}
