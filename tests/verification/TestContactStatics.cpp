// Rigid tools against closed forms once static (DynamicRelaxation): a frictionless plate
// compressing a neo-Hookean cube gives the uniaxial solution (lateral stretch and force), HEML and
// TLED, tetrahedra and hexahedra, in one load step and along keyframes.
#include "RigidTool.h"
#include "StaticSupport.h"

using namespace statics;
using fascia::Vec3;

namespace {

const char* kSolver = R"(<DynamicRelaxation name="dr" tolerance="1e-11" displacementTolerance="1e-11"/>)";

/// The unit cube of StaticSupport.h on rollers at xmin, ymin and zmin, its top pressed by a
/// frictionless PlaneTool (normal -z: the cube below it) whose pose is `motion`.
std::string plateScene(const std::string& ff, const std::string& element, const std::string& motion,
                       const std::string& rootExtra = "dt=\"1\"") {
    return R"(<Node name="root" )" + rootExtra + R"(>
  <Node name="cube">
    <GridMesh name="grid" min="0 0 0" max="1 1 1" resolution="3 3 3" element=")" + element + R"("/>
    <MechanicalObject name="state"/>
    <LumpedMass density="1000"/>
    <NeoHookean name="mat" mu="1000" kappa="5000"/>
    <)" + ff + R"( name="ff"/>
    )" + kSolver + R"(
    <FixedConstraint name="xmin" group="xmin" directions="1 0 0"/>
    <FixedConstraint name="ymin" group="ymin" directions="0 1 0"/>
    <FixedConstraint name="zmin" group="zmin" directions="0 0 1"/>
    <PlaneTool name="plate" normal="0 0 -1" )" + motion + R"(/>
  </Node>
</Node>)";
}

fascia::contact::RigidTool& plate(Simulation& sim) {
    auto* t = dynamic_cast<fascia::contact::RigidTool*>(&sim.tool("plate"));
    REQUIRE(t);
    return *t;
}

} // namespace

TEST_CASE("A frictionless plate compresses a cube to the uniaxial closed form once static", "[PlaneTool][DynamicRelaxation]") {
    const auto [ff, element] = GENERATE(table<std::string, std::string>({{"HEMLForceField", "tetrahedra6"},
                                                                          {"TLEDForceField", "tetrahedra6"},
                                                                          {"TLEDForceField", "hexahedra"}}));
    const double lambda = 0.8;
    CAPTURE(ff, element);
    // four load steps of 5 % (in one, the top layer of TLED's tetrahedra, squashed by 60 % before it
    // relaxes, shows a negative stiffness to the solver's first estimate)
    auto sim = Simulation::fromString(plateScene(ff, element, "keyTimes=\"0 4\" keyPositions=\"0 0 1  0 0 0.8\""));
    sim->run(4);
    const UniaxialNeoHookean ref(1000, 5000, lambda);  // closed form in StaticSupport.h
    const auto& rep = solver(*sim).reports().at(3);
    CAPTURE(rep.iterations, rep.residual, ref.a, ref.Pzz);
    REQUIRE(rep.converged);
    // the lateral stretch a and the plate's force -P_zz A0 (A0 = 1 m^2, the body pushes the plate up)
    CHECK(ref.a > 1.01);
    CHECK(homogeneousError(sim->state("state"), ref.a, lambda) < 1e-6);
    CHECK(plate(*sim).force()[2] == Approx(-ref.Pzz).epsilon(1e-6));
    CHECK(std::abs(plate(*sim).force()[0]) < 1e-6 * std::abs(ref.Pzz));
    CHECK(std::abs(plate(*sim).force()[1]) < 1e-6 * std::abs(ref.Pzz));
    CHECK(plate(*sim).contactCount() == 16);  // the top face's 4 x 4 nodes
    CHECK(reactionZ(*sim, "zmin") == Approx(-ref.Pzz).epsilon(1e-6));  // the support pushes up
}

TEST_CASE("A plate moved by keyframes gives the closed form at each load step", "[PlaneTool][DynamicRelaxation]") {
    auto sim = Simulation::fromString(plateScene("HEMLForceField", "tetrahedra6", "keyTimes=\"0 2\" keyPositions=\"0 0 1  0 0 0.8\""));
    for (double lambda : {0.9, 0.8}) {
        sim->step();
        const UniaxialNeoHookean ref(1000, 5000, lambda);
        CAPTURE(lambda);
        REQUIRE(solver(*sim).reports().back().converged);
        CHECK(homogeneousError(sim->state("state"), ref.a, lambda) < 1e-6);
        CHECK(plate(*sim).force()[2] == Approx(-ref.Pzz).epsilon(1e-6));
    }
}

