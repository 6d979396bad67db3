// TLEDForceField in a whole scene (XML, mesh source, mass, integrator, constraints): the TLED paper's
// section 6.2 compression-relaxation of a 0.1 m cube with the transversely isotropic viscoelastic
// liver model, laterally free (rollers), against the homogeneous quasi-static reference; hexahedra in
// bending; and the exporter with a TLED and a HEML force field on one state.
#include "fascia/base/Error.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace core = fascia::core;
namespace fs = std::filesystem;

namespace {

const char* kScene = R"(<Node name="root" dt="auto" dtSafety="0.5">
  <Node name="cube">
    <GridMesh name="grid" min="0 0 0" max="0.1 0.1 0.1" resolution="3 3 3" element="hexahedra"/>
    <MechanicalObject name="state"/>
    <LumpedMass density="1000"/>
    <TransverselyIsotropic name="liver" mu="6567" kappa="326210" eta="13134" direction="0 0 1"/>
    <ViscoelasticProny name="visco" alpha="0.5" tau="0.58" apply="isochoric"/>
    <TLEDForceField name="tled" mesh="@grid.mesh" hourglassStiffness="0.075"/>
    <CentralDifference damping="40"/>
    <FixedConstraint name="bottom" group="zmin" directions="0 0 1"/>
    <PrescribedDisplacement name="top" group="zmax" displacement="0 0 -0.03" shape="rampHold" rampTime="0.5" directions="0 0 1"/>
  </Node>
</Node>)";

double reactionZ(core::Simulation& sim, const std::string& constraint) {
    auto* c = dynamic_cast<core::BaseConstraint*>(sim.find(constraint));
    REQUIRE(c);
    const auto& r = sim.state("state").reaction();
    double fz = 0;
    for (int i : c->constrainedNodes()) fz += r[static_cast<size_t>(i)].z();
    return fz;
}

} // namespace

TEST_CASE("TLEDForceField relaxes a compressed cube like the homogeneous reference (TLED section 6.2)",
          "[TLEDForceField][scene]") {
    auto sim = core::Simulation::fromString(kScene, "relaxation.xml");
    auto* ff = dynamic_cast<core::BaseForceField*>(sim->find("tled"));
    REQUIRE(ff);
    CHECK(ff->elementCount() == 27);
    REQUIRE(ff->hexahedra());
    CHECK(ff->hexahedra()->size() == 27);
    // dt = 0.5 * L / c, L = V / A_max = 0.1/3 m, c = sqrt((kappa + 4/3 mu + eta) / rho)
    const double c = std::sqrt((326210 + 4.0 / 3.0 * 6567 + 13134) / 1000.0);
    CHECK(sim->dt() == Approx(0.5 * (0.1 / 3) / c).epsilon(1e-9));

    // reference (tests/reference/relaxation.txt, case TI-V-z): reaction on the loaded face
    // Fz = P_zz * A0 at t = 1 s and 5 s (exact hereditary integral, quasi-static)
    const double Fz1 = -86.252190, Fz5 = -67.309324;
    const long n1 = std::lround(1.0 / sim->dt()), n5 = std::lround(5.0 / sim->dt());
    sim->run(n1);
    const double r1 = reactionZ(*sim, "top");
    sim->run(n5 - n1);
    const double r5 = reactionZ(*sim, "top");
    CAPTURE(sim->time(), r1, r5);
    // the rollers carry the same force the other way
    CHECK(reactionZ(*sim, "bottom") == Approx(-r5).epsilon(1e-3));
    CHECK(r1 == Approx(Fz1).epsilon(2e-3));  // dynamics (inertia, damping) and time sampling
    CHECK(r5 == Approx(Fz5).epsilon(2e-4));
    // the cube stays homogeneous: every element has the same J (the reference's 0.99516 at 5 s)
    std::vector<core::CellField> cells;
    ff->cellData(sim->state("state"), cells);
    const core::CellField* J = nullptr;
    for (auto& f : cells)
        if (f.name == "J") J = &f;
    REQUIRE(J);
    for (double v : J->values) CHECK(v == Approx(0.99516225).epsilon(1e-6));
}

namespace {

std::string relaxationScene(const std::string& material) {
    return std::string(R"(<Node name="root" dt="auto" dtSafety="0.5">
  <Node name="cube">
    <GridMesh name="grid" min="0 0 0" max="0.1 0.1 0.1" resolution="3 3 3" element="hexahedra"/>
    <MechanicalObject name="state"/>
    <LumpedMass density="1000"/>
    )") + material + R"(
    <ViscoelasticProny name="visco" alpha="0.5" tau="0.58" apply="isochoric"/>
    <TLEDForceField name="tled"/>
    <CentralDifference damping="40"/>
    <FixedConstraint name="bottom" group="zmin" directions="0 0 1"/>
    <PrescribedDisplacement name="top" group="zmax" displacement="0 0 -0.03" shape="rampHold" rampTime="0.5" directions="0 0 1"/>
  </Node>
</Node>)";
}

/// Lateral stretches (width / 0.1 m) along x and y.
std::pair<double, double> lateralStretch(core::Simulation& sim) {
    const auto& x = sim.state("state").x();
    double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
    for (auto& p : x)
        for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
    return {(hi[0] - lo[0]) / 0.1, (hi[1] - lo[1]) / 0.1};
}

struct RelaxationCase {
    const char* name;
    const char* material;
    double Fz[3];  // reaction at 1, 2, 5 s (tests/reference/relaxation.txt)
    double lx, ly; // lateral stretches at 5 s
};

} // namespace

TEST_CASE("TLED section 6.2: reaction histories and lateral expansion of the isotropic and fibre-reinforced cubes",
          "[TLEDForceField][scene][verification]") {
    // tests/reference/relaxation.txt, the homogeneous quasi-static reference (load along z): ISO-V,
    // TI-V-z (fibre along the load) and TI-V-x (fibre across the load: the paper's a0 = [0 1 0] with
    // its load along x; Fig. 3c, expansion much reduced along the fibre)
    const RelaxationCase c = GENERATE(
        RelaxationCase{"ISO-V", R"(<NeoHookean mu="6567" kappa="326210"/>)", {-56.942932, -46.238069, -43.920178}, 1.19334382, 1.19334382},
        RelaxationCase{"TI-V-z", R"(<TransverselyIsotropic mu="6567" kappa="326210" eta="13134" direction="0 0 1"/>)",
                       {-86.252190, -70.677993, -67.309324}, 1.19233400, 1.19233400},
        RelaxationCase{"TI-V-x", R"(<TransverselyIsotropic mu="6567" kappa="326210" eta="13134" direction="1 0 0"/>)",
                       {-73.140831, -59.323980, -56.325646}, 1.09535878, 1.29892845});
    CAPTURE(c.name);
    auto sim = core::Simulation::fromString(relaxationScene(c.material), "relaxation.xml");
    const double times[3] = {1.0, 2.0, 5.0}, tol[3] = {2e-3, 5e-4, 2e-4};
    for (int k = 0; k < 3; ++k) {
        sim->run(std::lround(times[k] / sim->dt()) - sim->stepCount());
        const double fz = reactionZ(*sim, "top");
        CAPTURE(times[k], fz);
        CHECK(fz == Approx(c.Fz[k]).epsilon(tol[k]));
    }
    const auto [lx, ly] = lateralStretch(*sim);
    CHECK(lx == Approx(c.lx).epsilon(1e-4));
    CHECK(ly == Approx(c.ly).epsilon(1e-4));
}

TEST_CASE("TLED section 6.2: a fibre at 45 degrees in the lateral plane reduces the expansion along it",
          "[TLEDForceField][scene][verification]") {
    // the paper's a0 = [0 1 1]/sqrt(2) with its load along x is a0 = [1 1 0]/sqrt(2) with ours along z
    // (Fig. 3d). A homogeneous problem rotated about the load axis: the reaction equals TI-V-x's and the
    // stretches along a0 and across it are TI-V-x's lx and ly (the width of the deformed square along an
    // eigenvector d of F scales by its eigenvalue).
    auto sim = core::Simulation::fromString(
        relaxationScene(R"(<TransverselyIsotropic mu="6567" kappa="326210" eta="13134" direction="1 1 0"/>)"), "relaxation.xml");
    sim->run(std::lround(5.0 / sim->dt()));
    const double fz = reactionZ(*sim, "top");
    CHECK(fz == Approx(-56.325646).epsilon(2e-4));
    auto width = [&](const fascia::Vec3& d) {
        double lo = 1e9, hi = -1e9;
        for (auto& p : sim->state("state").x()) lo = std::min(lo, p.dot(d)), hi = std::max(hi, p.dot(d));
        return (hi - lo) / (0.1 * std::sqrt(2.0));
    };
    const double along = width(fascia::Vec3(1, 1, 0).normalized()), across = width(fascia::Vec3(1, -1, 0).normalized());
    CAPTURE(fz, along, across);
    CHECK(along == Approx(1.09535878).epsilon(1e-4));
    CHECK(across == Approx(1.29892845).epsilon(1e-4));
}

TEST_CASE("TLED hexahedra in bending: hourglass control suppresses the zero-energy modes",
          "[TLEDForceField][scene][verification]") {
    // a cantilever 0.2 x 0.02 x 0.02 m, two one-point hexahedra through its depth, a tip load of 1 mN:
    // Euler-Bernoulli gives F L^3 / (3 E I) = 2.0 mm, Timoshenko adds F L / (5/6 G A) = 0.0156 mm.
    // Without control the hourglass modes of the reduced integration carry the load almost freely;
    // with the Flanagan-Belytschko control the beam bends like a beam, too stiff on this coarse mesh
    // by a known amount: this is the 10 x 2 x 2 mesh of the convergence study in
    // tests/verification/TestCantilever.cpp, which measured 1.379 mm, 31.6 % below Timoshenko, and
    // whose finer meshes converge to Timoshenko. The controlled bound is that study's [30 %, 33 %].
    auto tip = [](const std::string& hourglass) {
        auto sim = core::Simulation::fromString(R"(<Node name="root" dt="auto" dtSafety="0.5">
  <GridMesh min="0 0 0" max="0.2 0.02 0.02" resolution="10 2 2" element="hexahedra"/>
  <MechanicalObject name="state"/>
  <LumpedMass density="1000"/>
  <NeoHookean youngModulus="100000" poissonRatio="0.3"/>
  <TLEDForceField name="ff" hourglassStiffness=")" + hourglass + R"("/>
  <CentralDifference damping="10"/>
  <FixedConstraint group="xmin"/>
  <ConstantForce name="load" group="xmax" totalForce="0 0 -0.001"/>
</Node>)");
        sim->run(std::lround(10.0 / sim->dt()));
        const auto& st = sim->state("state");
        double w = 0, lo = 1e9, hi = -1e9;  // mean tip deflection and its spread over the tip face
        int n = 0;
        for (size_t i = 0; i < st.size(); ++i)
            if (st.x0()[i].x() > 0.2 - 1e-12) {
                const double d = st.x()[i].z() - st.x0()[i].z();
                w += d, ++n, lo = std::min(lo, d), hi = std::max(hi, d);
            }
        return std::make_pair(-w / n, hi - lo);
    };
    const double beam = 1e-3 * 0.2 * 0.2 * 0.2 / (3 * 1e5 * std::pow(0.02, 4) / 12);
    const double timoshenko = beam + 1e-3 * 0.2 / (5.0 / 6.0 * 1e5 / (2 * 1.3) * 0.02 * 0.02);
    const auto [controlled, controlledSpread] = tip("0.075");
    const auto [free, freeSpread] = tip("0");
    const double controlledError = 1 - controlled / timoshenko;
    CAPTURE(beam, timoshenko, controlled, controlledError, controlledSpread, free, freeSpread);
    CHECK(controlledError > 0.30);  // stiff by the coarse-mesh error of TestCantilever.cpp,
    CHECK(controlledError < 0.33);  // and no more
    CHECK(controlledSpread < 0.05 * controlled);  // the tip face moves as a whole
    CHECK(free > 2 * beam);                       // without control: far too soft,
    CHECK(freeSpread > 2 * free);                 // and the tip face zigzags (hourglass pattern)
}

TEST_CASE("TLEDForceField scene errors are located at the element's line", "[TLEDForceField][scene]") {
    const char* bad = R"(<Node name="root" dt="0.001">
  <GridMesh name="grid" resolution="1 1 1"/>
  <MechanicalObject name="state"/>
  <LumpedMass density="1000"/>
  <TLEDForceField name="tled" fibreArray="fibres"/>
  <CentralDifference/>
</Node>)";
    try {
        core::Simulation::fromString(bad, "bad.xml");
        FAIL("no error");
    } catch (const core::Error& e) {
        const std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find("bad.xml:5: error: TLEDForceField 'tled':") != std::string::npos);
    }
}

TEST_CASE("VTKExporter writes the cells and cell data of every element force field on the state",
          "[TLEDForceField][scene][VTKExporter]") {
    // HEML on the 162 tetrahedra of one grid, TLED on the 27 hexahedra of a second grid over the same
    // nodes, both acting on one state
    const fs::path dir = fs::temp_directory_path() / ("fascia-tled-export-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    auto sim = core::Simulation::fromString(R"(<Node name="root" dt="0.0001">
  <GridMesh name="tets" min="0 0 0" max="0.1 0.1 0.1" resolution="3 3 3" element="tetrahedra6"/>
  <GridMesh name="hexes" min="0 0 0" max="0.1 0.1 0.1" resolution="3 3 3" element="hexahedra"/>
  <MechanicalObject name="state" position="@tets.positions"/>
  <LumpedMass density="1000"/>
  <NeoHookean youngModulus="3000" poissonRatio="0.45"/>
  <HEMLForceField name="heml" tetrahedra="@tets.tetrahedra"/>
  <TLEDForceField name="tled" hexahedra="@hexes.hexahedra"/>
  <SemiImplicitEuler/>
  <FixedConstraint group="zmin"/>
  <ConstantForce group="zmax" totalForce="0 0 -0.5"/>
  <VTKExporter name="out" every="5"/>
</Node>)",
                                            "export.xml", ".", {dir.string(), 0});
    sim->run(5);
    sim->finish();
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir / "out_000005.vtu").string().c_str());
    reader->Update();
    vtkUnstructuredGrid* g = reader->GetOutput();
    REQUIRE(g->GetNumberOfCells() == 162 + 27);
    for (vtkIdType c = 0; c < 162 + 27; ++c) CHECK(g->GetCellType(c) == (c < 162 ? 10 : 12));  // VTK_TETRA, VTK_HEXAHEDRON
    vtkDataArray* owner = g->GetCellData()->GetArray("forceField");
    vtkDataArray* J = g->GetCellData()->GetArray("J");
    vtkDataArray* S = g->GetCellData()->GetArray("S");
    REQUIRE(owner);
    REQUIRE(J);
    REQUIRE(S);
    // each force field's own values in its own cells
    std::vector<core::CellField> heml, tled;
    dynamic_cast<core::BaseForceField*>(sim->find("heml"))->cellData(sim->state("state"), heml);
    dynamic_cast<core::BaseForceField*>(sim->find("tled"))->cellData(sim->state("state"), tled);
    auto field = [](const std::vector<core::CellField>& fs, const std::string& name) {
        for (auto& f : fs)
            if (f.name == name) return f.values;
        FAIL("no cell field " << name);
        return std::vector<double>{};
    };
    const auto Jh = field(heml, "J"), Jt = field(tled, "J"), St = field(tled, "S");
    bool deformed = false;
    for (vtkIdType c = 0; c < 162; ++c) {
        CHECK(owner->GetTuple1(c) == 0);
        CHECK(J->GetTuple1(c) == Jh[size_t(c)]);
        deformed = deformed || J->GetTuple1(c) != 1;
        CHECK(std::isnan(S->GetComponent(c, 0)));  // HEML offers no S
    }
    for (vtkIdType c = 0; c < 27; ++c) {
        CHECK(owner->GetTuple1(162 + c) == 1);
        CHECK(J->GetTuple1(162 + c) == Jt[size_t(c)]);
        for (int k = 0; k < 6; ++k) CHECK(S->GetComponent(162 + c, k) == St[6 * size_t(c) + size_t(k)]);
    }
    CHECK(deformed);
    fs::remove_all(dir);
}
