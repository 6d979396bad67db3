// DynamicRelaxation (Joldes, Wittek and Miller 2009) against analytic static solutions, with no
// damping given: uniaxial stretch of a neo-Hookean cube (HEML, TLED tetrahedra, TLED hexahedra), a
// Mooney-Rivlin tetrahedron under a nodal force (against an independent Newton solve written here),
// a cube under follower pressure, load steps along a ramp, and the independence from the declared mass.
#include "StaticSupport.h"

#include <Eigen/Dense>

#include <array>
#include <vector>

using namespace statics;
using fascia::Vec3;

namespace {

const char* kSolver = R"(<DynamicRelaxation name="dr" tolerance="1e-11" displacementTolerance="1e-11"/>)";

} // namespace

TEST_CASE("DynamicRelaxation stretches a neo-Hookean cube to the closed-form lateral stretch and stress",
          "[DynamicRelaxation]") {
    const auto [ff, element] = GENERATE(table<std::string, std::string>({{"HEMLForceField", "tetrahedra6"},
                                                                          {"TLEDForceField", "tetrahedra6"},
                                                                          {"TLEDForceField", "hexahedra"}}));
    const double lambda = GENERATE(0.7, 1.5);
    CAPTURE(ff, element, lambda);
    auto sim = Simulation::fromString(stretchScene(ff, element, lambda, kSolver));
    sim->step();
    const UniaxialNeoHookean ref(1000, 5000, lambda);
    const auto& rep = solver(*sim).reports().at(0);
    CAPTURE(rep.iterations, rep.residual, rep.rate, ref.a, ref.Pzz);
    REQUIRE(rep.converged);
    CHECK(rep.loadStep == 1);
    CHECK(rep.time == 1.0);
    CHECK(rep.iterations > 10);
    CHECK(rep.residual <= 1e-11);
    CHECK(rep.rate > 0);
    CHECK(rep.rate < 1);
    // positions to 1e-8 of the body's size, the top reaction (P_zz A0, A0 = 1 m^2) to 1e-8 relative
    CHECK(homogeneousError(sim->state("state"), ref.a, lambda) < 1e-8);
    CHECK(reactionZ(*sim, "top") == Approx(ref.Pzz).epsilon(1e-8));
    CHECK(reactionZ(*sim, "zmin") == Approx(-ref.Pzz).epsilon(1e-8));
    // a static solution is at rest
    for (auto& v : sim->state("state").v()) CHECK(v.norm() == 0);
}

TEST_CASE("DynamicRelaxation solves each load step of a ramp from the previous solution", "[DynamicRelaxation]") {
    // a ramp of the top displacement to 1.4 over 1 s sampled at dt = 0.25: four static load steps
    auto sim = Simulation::fromString(stretchScene("TLEDForceField", "tetrahedra6", 1.4, kSolver, "dt=\"0.25\""));
    sim->run(4);
    const auto& reps = solver(*sim).reports();
    REQUIRE(reps.size() == 4);
    long total = 0;
    for (size_t k = 0; k < 4; ++k) {
        CAPTURE(k);
        CHECK(reps[k].loadStep == long(k + 1));
        CHECK(reps[k].time == Approx(0.25 * double(k + 1)).epsilon(1e-15));
        CHECK(reps[k].converged);
        total += reps[k].iterations;
    }
    CHECK(solver(*sim).totalIterations() == total);
    const UniaxialNeoHookean ref(1000, 5000, 1.4);
    CHECK(homogeneousError(sim->state("state"), ref.a, 1.4) < 1e-8);
    // a fifth step holds the load: the previous solution is already in equilibrium, no iteration
    sim->step();
    REQUIRE(reps.size() == 5);
    CHECK(reps[4].converged);
    CHECK(reps[4].iterations == 0);
    CHECK(solver(*sim).runSummary().find("5 load steps") != std::string::npos);
    CHECK(solver(*sim).runSummary().find("all converged") != std::string::npos);
    CHECK_FALSE(solver(*sim).runFailed());
}

TEST_CASE("DynamicRelaxation gives the same solution whatever mass the scene declares", "[DynamicRelaxation]") {
    auto light = Simulation::fromString(stretchScene("TLEDForceField", "tetrahedra6", 1.3, kSolver, "dt=\"1\"", "0.001"));
    auto heavy = Simulation::fromString(stretchScene("TLEDForceField", "tetrahedra6", 1.3, kSolver, "dt=\"1\"", "1e6"));
    light->step();
    heavy->step();
    const auto& a = light->state("state");
    const auto& b = heavy->state("state");
    double diff = 0;
    for (size_t i = 0; i < a.size(); ++i) diff = std::max(diff, (a.x()[i] - b.x()[i]).norm());
    CHECK(diff < 1e-10);
    // the fictitious mass takes the declared mass's shape only: the same iterations
    const long na = solver(*light).reports().at(0).iterations, nb = solver(*heavy).reports().at(0).iterations;
    CHECK(std::abs(na - nb) <= 2);
}

namespace {

// ---- a Mooney-Rivlin tetrahedron: the reference, an independent Newton solve ----
// W = C1 (I1bar - 3) + C2 (I2bar - 3) + kappa/2 (J - 1)^2 (fascia/materials/CompressibleMooneyRivlin.h)
// P = dW/dF = C1 dI1bar/dF + C2 dI2bar/dF + kappa (J - 1) J F^-T, with
//   dI1bar/dF = J^(-2/3) (2 F - 2/3 I1 F^-T), dI2bar/dF = J^(-4/3) (2 (I1 F - F C) - 4/3 I2 F^-T).
// Nodal forces of a linear tetrahedron: f_a = -V0 P dN_a/dX.
const double kC1 = 300, kC2 = 150, kKappa = 4000;
const std::array<Vec3, 4> kX = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
const Vec3 kLoad(60, -40, 120);  // on node 3 (N)
// free components (node, axis): node 0 fixed, node 1 moves along x only, node 2 in the x-y plane
const std::array<std::pair<int, int>, 6> kFree = {{{1, 0}, {2, 0}, {2, 1}, {3, 0}, {3, 1}, {3, 2}}};

Eigen::Matrix3d mooneyRivlinP(const Eigen::Matrix3d& F) {
    const double J = F.determinant();
    const Eigen::Matrix3d C = F.transpose() * F, FinvT = F.inverse().transpose();
    const double I1 = C.trace(), I2 = 0.5 * (I1 * I1 - (C * C).trace());
    const Eigen::Matrix3d dI1bar = std::pow(J, -2.0 / 3.0) * (2 * F - 2.0 / 3.0 * I1 * FinvT);
    const Eigen::Matrix3d dI2bar = std::pow(J, -4.0 / 3.0) * (2 * (I1 * F - F * C) - 4.0 / 3.0 * I2 * FinvT);
    return kC1 * dI1bar + kC2 * dI2bar + kKappa * (J - 1) * J * FinvT;
}

/// Residual (internal + external force) at the free components for positions x.
Eigen::Matrix<double, 6, 1> tetResidual(const std::array<Vec3, 4>& x) {
    Eigen::Matrix3d Dm, Ds;
    for (int k = 0; k < 3; ++k) Dm.col(k) = kX[k + 1] - kX[0], Ds.col(k) = x[k + 1] - x[0];
    const double V0 = Dm.determinant() / 6;
    const Eigen::Matrix3d F = Ds * Dm.inverse(), P = mooneyRivlinP(F);
    // dN_a/dX for a = 1..3 are the rows of Dm^-1; dN_0/dX = -(their sum)
    const Eigen::Matrix3d G = Dm.inverse();
    std::array<Vec3, 4> f;
    f[0] = Vec3::Zero();
    for (int a = 1; a <= 3; ++a) {
        f[a] = -V0 * P * G.row(a - 1).transpose();
        f[0] -= f[a];
    }
    f[3] += kLoad;
    Eigen::Matrix<double, 6, 1> r;
    for (int k = 0; k < 6; ++k) r[k] = f[kFree[k].first][kFree[k].second];
    return r;
}

std::array<Vec3, 4> tetNewton() {
    std::array<Vec3, 4> x = kX;
    for (int it = 0; it < 50; ++it) {
        const auto r = tetResidual(x);
        Eigen::Matrix<double, 6, 6> K;
        for (int j = 0; j < 6; ++j) {
            const double h = 1e-6;
            auto xp = x, xm = x;
            xp[kFree[j].first][kFree[j].second] += h;
            xm[kFree[j].first][kFree[j].second] -= h;
            K.col(j) = (tetResidual(xp) - tetResidual(xm)) / (2 * h);
        }
        const Eigen::Matrix<double, 6, 1> dx = K.fullPivLu().solve(-r);
        for (int k = 0; k < 6; ++k) x[kFree[k].first][kFree[k].second] += dx[k];
        if (dx.norm() < 1e-15) break;
    }
    return x;
}

std::string tetScene(const std::string& ff, const std::string& solverXml) {
    return R"(<Node name="root" dt="1">
  <MechanicalObject name="state" position="0 0 0  1 0 0  0 1 0  0 0 1"/>
  <LumpedMass totalMass="4"/>
  <CompressibleMooneyRivlin name="mat" C1="300" C2="150" kappa="4000"/>
  <)" + ff + R"( name="ff" tetrahedra="0 1 2 3"/>
  )" + solverXml + R"(
  <FixedConstraint name="n0" indices="0"/>
  <FixedConstraint name="n1" indices="1" directions="0 1 1"/>
  <FixedConstraint name="n2" indices="2" directions="0 0 1"/>
  <ConstantForce name="load" indices="3" force="60 -40 120"/>
</Node>)";
}

} // namespace

TEST_CASE("DynamicRelaxation puts a Mooney-Rivlin tetrahedron under a nodal force where a Newton solve does",
          "[DynamicRelaxation]") {
    const std::string ff = GENERATE(as<std::string>{}, "TLEDForceField", "HEMLForceField");
    CAPTURE(ff);
    const auto ref = tetNewton();
    REQUIRE(tetResidual(ref).norm() < 1e-10);
    double size = 0;
    for (int a = 0; a < 4; ++a) size = std::max(size, (ref[a] - kX[a]).norm());
    REQUIRE(size > 0.05);  // a large deformation, not a linear one
    auto sim = Simulation::fromString(tetScene(ff, kSolver));
    sim->step();
    const auto& rep = solver(*sim).reports().at(0);
    CAPTURE(rep.iterations, rep.residual, rep.rate);
    REQUIRE(rep.converged);
    const auto& s = sim->state("state");
    for (int a = 0; a < 4; ++a) {
        CAPTURE(a, s.x()[a].transpose(), ref[a].transpose());
        CHECK((s.x()[a] - ref[a]).norm() < 1e-8 * size);
    }
}

namespace {

std::string pressureScene(const std::string& element, double p, const std::string& solverXml) {
    std::string loads;
    for (const char* face : {"xmax", "ymax", "zmax"})
        loads += std::string("  <SurfacePressure name=\"p") + face + "\" nodeGroup=\"" + face + "\" pressure=\"" +
                 std::to_string(p) + "\"/>\n";
    return R"(<Node name="root" dt="1">
  <GridMesh name="grid" min="0 0 0" max="1 1 1" resolution="3 3 3" element=")" + element + R"("/>
  <MechanicalObject name="state"/>
  <LumpedMass density="1000"/>
  <NeoHookean name="mat" mu="1000" kappa="5000"/>
  <TLEDForceField name="ff"/>
  )" + solverXml + R"(
  <FixedConstraint name="xmin" group="xmin" directions="1 0 0"/>
  <FixedConstraint name="ymin" group="ymin" directions="0 1 0"/>
  <FixedConstraint name="zmin" group="zmin" directions="0 0 1"/>
)" + loads + "</Node>";
}

} // namespace

TEST_CASE("DynamicRelaxation shrinks a cube under follower pressure to the volume where p = -dW/dJ",
          "[DynamicRelaxation][SurfacePressure]") {
    // F = s I: the isochoric part carries no stress, sigma = kappa (J - 1) I = -p I, so J = 1 - p/kappa
    const double p = GENERATE(500.0, 1500.0);
    const std::string element = GENERATE(as<std::string>{}, "tetrahedra6", "hexahedra");
    CAPTURE(p, element);
    auto sim = Simulation::fromString(pressureScene(element, p, kSolver));
    sim->step();
    const auto& rep = solver(*sim).reports().at(0);
    CAPTURE(rep.iterations, rep.residual, rep.rate);
    REQUIRE(rep.converged);
    const double J = 1 - p / 5000, s = std::cbrt(J);
    CHECK(homogeneousError(sim->state("state"), s, s) < 1e-8);
}

TEST_CASE("DynamicRelaxation stops at its force and displacement tolerances", "[DynamicRelaxation]") {
    auto iterate = [](const std::string& attrs) {
        auto sim = Simulation::fromString(
            stretchScene("TLEDForceField", "tetrahedra6", 1.5, "<DynamicRelaxation name=\"dr\" " + attrs + "/>"));
        sim->step();
        const UniaxialNeoHookean ref(1000, 5000, 1.5);
        auto rep = solver(*sim).reports().at(0);
        return std::make_pair(rep, homogeneousError(sim->state("state"), ref.a, 1.5));
    };
    const auto [tight, tightErr] = iterate("tolerance=\"1e-10\" displacementTolerance=\"1e-10\"");
    // a loose force tolerance: it stops when the displacement criterion (tight) holds
    const auto [looseForce, lfErr] = iterate("tolerance=\"1e-3\" displacementTolerance=\"1e-10\"");
    // both loose: far fewer iterations, a residual below the loose tolerance only
    const auto [loose, looseErr] = iterate("tolerance=\"1e-3\" displacementTolerance=\"1e-3\"");
    CAPTURE(tight.iterations, looseForce.iterations, loose.iterations, tightErr, lfErr, looseErr);
    REQUIRE(tight.converged);
    REQUIRE(looseForce.converged);
    REQUIRE(loose.converged);
    CHECK(tight.residual <= 1e-10);
    CHECK(tight.displacementError <= 1e-10);
    CHECK(loose.residual <= 1e-3);
    CHECK(loose.residual > 1e-10);
    CHECK(loose.displacementError <= 1e-3);
    CHECK(loose.iterations < tight.iterations / 2);
    CHECK(looseErr > 1e3 * tightErr);
    // the displacement tolerance alone keeps it iterating where the force tolerance would have stopped
    CHECK(looseForce.displacementError <= 1e-10);
    CHECK(looseForce.iterations > loose.iterations);
    CHECK(lfErr < 1e-7);
}

TEST_CASE("DynamicRelaxation settles a column under its own weight to the bar solution", "[DynamicRelaxation]") {
    // nu = 0 (kappa = 2 mu / 3, E = 2 mu), small strain: a bar, u_z(z) = -rho g / E (H z - z^2 / 2). The
    // regular hexahedra (TLED) with the lumped nodal loads (those of a uniform body force on them) and
    // a displacement linear in z in each layer are a chain of 1D linear elements, exact at the nodes
    const double E = 1e10, rho = 1000, g = 9.81, H = 1;
    auto sim = Simulation::fromString(R"(<Node name="root" dt="1" gravity="0 0 -9.81">
  <GridMesh name="grid" min="0 0 0" max="1 1 1" resolution="2 2 4" element="hexahedra"/>
  <MechanicalObject name="state"/>
  <LumpedMass density="1000"/>
  <NeoHookean name="mat" mu="5e9" kappa="3.3333333333333333e9"/>
  <TLEDForceField name="ff"/>
  <DynamicRelaxation name="dr" tolerance="1e-10" displacementTolerance="1e-10"/>
  <FixedConstraint name="xmin" group="xmin" directions="1 0 0"/>
  <FixedConstraint name="ymin" group="ymin" directions="0 1 0"/>
  <FixedConstraint name="zmin" group="zmin" directions="0 0 1"/>
</Node>)");
    sim->step();
    const auto& rep = solver(*sim).reports().at(0);
    CAPTURE(rep.iterations, rep.residual);
    REQUIRE(rep.converged);
    const auto& s = sim->state("state");
    const double top = -rho * g * H * H / (2 * E);
    for (size_t i = 0; i < s.size(); ++i) {
        const double z = s.x0()[i].z(), expected = -rho * g / E * (H * z - 0.5 * z * z);
        CAPTURE(i, z);
        CHECK(s.x()[i].z() - z == Approx(expected).margin(1e-5 * std::abs(top)));
    }
}
