// TLEDForceField: conformance on every material and element type, the hexahedron patch and
// hourglass tests, stresses and cell data, time steps, groups and fibre arrays, input errors, and
// bitwise determinism across thread counts.
#include "TLEDTestSupport.h"

#include "fascia/base/Error.h"

#include "fascia/materials/Conformance.h"

#include <catch2/catch.hpp>

#include <omp.h>

#include <cmath>
#include <ctime>
#include <numeric>
#include <random>

using namespace tledtest;

namespace {

enum class MeshKind { Tets, Hexes, Mixed };

std::string meshName(MeshKind k) { return k == MeshKind::Tets ? "tetrahedra" : k == MeshKind::Hexes ? "hexahedra" : "mixed"; }

/// A 2x2x2 cube of side 0.1 m: tetrahedra, hexahedra, or hexahedra below and tetrahedra above.
void cubeMesh(MeshKind k, Positions& p, Tetrahedra& t, Hexahedra& h) {
    p = gridPoints(2, 2, 2, 0.05);
    t.clear();
    h.clear();
    if (k == MeshKind::Tets) t = gridTets(2, 2, 2);
    if (k == MeshKind::Hexes) h = gridHexes(2, 2, 2);
    if (k == MeshKind::Mixed) {
        h = gridHexes(2, 2, 2, 0, 1);
        t = gridTets(2, 2, 2, 1, 2);
    }
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const fascia::core::Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("TLEDForceField forces are the gradient of its energy, vanish at rest and follow rigid motions",
          "[TLEDForceField][conformance]") {
    const std::string type = GENERATE(from_range(allMaterialTypes()));
    const MeshKind kind = GENERATE(MeshKind::Tets, MeshKind::Hexes, MeshKind::Mixed);
    CAPTURE(type, meshName(kind));
    Positions p;
    Tetrahedra t;
    Hexahedra h;
    cubeMesh(kind, p, t, h);
    Bench b(p);
    const auto& mat = b.material(type, defaultParams(type));
    b.forceField(t, h).init();
    CHECK(b.ff->usesFastPath());  // every built-in law runs its inlined loop

    materials::conformance::ForceFieldCheckOptions opt;
    const auto rep = materials::conformance::checkForceField(*b.ff, *b.state, opt);
    CAPTURE(rep.forceScale, rep.gradientError, rep.restForce, rep.rotationError, rep.energyRotationError, rep.worstNode);
    CHECK(rep.forceScale > 0);
    CHECK(rep.gradientError < 1e-6);
    CHECK(rep.rotationError < 1e-10);
    CHECK(rep.energyRotationError < 1e-10);
    if (mat.stressFreeAtRest()) {
        CHECK(rep.restForce < 1e-12);
    } else {
        // the HEML paper's "incompressible" laws carry a stress at rest (no pressure term): the
        // boundary nodes feel it, so the rest force is of the order of the force scale
        CHECK(rep.restForce > 1e-3);
    }
}

namespace {
// a material that is not a Material<Law>: the force field runs its generic loop for it
using Wrapped = materials::conformance::GenericMaterial;
} // namespace

TEST_CASE("TLEDForceField runs a law outside the built-in list through its generic loop with the same forces",
          "[TLEDForceField][conformance]") {
    const std::string type = GENERATE(from_range(allMaterialTypes()));
    const MeshKind kind = GENERATE(MeshKind::Tets, MeshKind::Hexes);
    CAPTURE(type, meshName(kind));
    Positions p;
    Tetrahedra t;
    Hexahedra h;
    cubeMesh(kind, p, t, h);
    const Mat3 F = (Mat3() << 1.08, 0.05, -0.02, 0.03, 0.93, 0.04, -0.01, 0.06, 1.02).finished();
    // the built-in law, inlined
    Bench a(p);
    a.material(type, defaultParams(type));
    a.forceField(t, h).init();
    a.deform(F);
    const Positions fa = a.forces();
    // the same material behind a wrapper that is not in materials::BuiltinMaterials
    Bench b(p);
    auto& mat = b.material(type, defaultParams(type), "inner");
    mat.init();
    auto& w = b.root.add<Wrapped>("wrapped");
    w.inner = &mat;
    b.forceField(t, h);
    b.ff->m_material.set(&w);
    b.ff->init();
    b.deform(F);
    const Positions fb = b.forces();
    CHECK(a.ff->usesFastPath());
    CHECK_FALSE(b.ff->usesFastPath());
    double err = 0, scale = 0;
    for (size_t i = 0; i < fa.size(); ++i) err = std::max(err, (fa[i] - fb[i]).norm()), scale = std::max(scale, fa[i].norm());
    CAPTURE(err, scale);
    CHECK(scale > 0);
    CHECK(err <= 1e-12 * scale);
}

TEST_CASE("TLEDForceField keeps its hourglass forces conservative and rotation-free on distorted hexahedra",
          "[TLEDForceField][conformance]") {
    Positions p = gridPoints(2, 2, 2, 0.05);
    // distort the interior and a few boundary nodes
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.01, 0.01);
    for (auto& x : p) x += Vec3(u(rng), u(rng), u(rng));
    Bench b(p);
    b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
    b.forceField({}, gridHexes(2, 2, 2), {{"hourglassStiffness", "0.3"}}).init();
    materials::conformance::ForceFieldCheckOptions opt;
    opt.amplitude = 0.1;  // large non-affine part: strong hourglass modes
    const auto rep = materials::conformance::checkForceField(*b.ff, *b.state, opt);
    CAPTURE(rep.gradientError, rep.restForce, rep.rotationError);
    CHECK(rep.gradientError < 1e-6);
    CHECK(rep.restForce < 1e-12);
    CHECK(rep.rotationError < 1e-10);
}

TEST_CASE("TLEDForceField computes the stress of a homogeneous deformation exactly on both element types",
          "[TLEDForceField]") {
    const std::string type = GENERATE(as<std::string>{}, "CompressibleNeoHookean", "CompressibleMooneyRivlin",
                                      "TransverselyIsotropic", "Orthotropic", "StVenantKirchhoff");
    CAPTURE(type);
    Positions p = gridPoints(1, 1, 2, 0.1);
    Bench b(p);
    const auto& mat = b.material(type, defaultParams(type));
    b.forceField(gridTets(1, 1, 2, 1, 2), gridHexes(1, 1, 2, 0, 1)).init();
    Mat3 F;
    F << 1.1, 0.2, -0.05, 0.03, 0.9, 0.1, -0.02, 0.07, 1.05;
    b.deform(F, Vec3(0.3, 0.1, -0.2));
    std::vector<double> S;
    b.ff->stresses(*b.state, 0, S);
    REQUIRE(S.size() == 6 * b.ff->elementCount());
    const Vec3* a0 = mat.fibreDirection(0);
    const Vec3* b0 = mat.fibreDirection(1);
    const Mat3 Sref = referenceS(mat, F, a0 ? *a0 : Vec3(0, 0, 1), b0 ? *b0 : Vec3(1, 0, 0));
    for (size_t e = 0; e < b.ff->elementCount(); ++e) {
        CAPTURE(e);
        CHECK((fromVoigt(&S[6 * e]) - Sref).norm() < 1e-10 * Sref.norm());
    }
    // potential energy = W(F) times the total volume (0.002 m^3)
    const auto in = materials::conformance::invariantsOf(F, a0 ? *a0 : Vec3(0, 0, 1), b0 ? *b0 : Vec3(1, 0, 0));
    const double W = materials::conformance::evaluateOne(mat, in, 0.4).W;
    CHECK(b.ff->potentialEnergy(*b.state) == Approx(W * 0.002).epsilon(1e-12));
    CHECK(b.ff->restVolume(0) == Approx(0.1 * 0.1 * 0.1 / 6).epsilon(1e-14));
    CHECK(b.ff->restVolume(6) == Approx(0.001).epsilon(1e-14));
}

TEST_CASE("TLEDForceField reports S, Cauchy stress, von Mises stress and J per element", "[TLEDForceField]") {
    Bench b(gridPoints(1, 1, 1, 1.0));
    const auto& mat = b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
    b.forceField(gridTets(1, 1, 1), {}).init();
    Mat3 F;
    F << 1.2, 0.1, 0, 0, 0.95, 0.05, 0, 0, 0.9;
    b.deform(F);
    std::vector<core::CellField> cells;
    b.ff->cellData(*b.state, cells);
    REQUIRE(cells.size() == 4);
    CHECK(cells[0].name == "S");
    CHECK(cells[1].name == "cauchyStress");
    CHECK(cells[2].name == "vonMises");
    CHECK(cells[3].name == "J");
    const Mat3 S = referenceS(mat, F);
    const double J = F.determinant();
    const Mat3 sig = F * S * F.transpose() / J;
    const Mat3 dev = sig - sig.trace() / 3 * Mat3::Identity();
    const double vm = std::sqrt(1.5 * (dev.array() * dev.array()).sum());
    for (size_t e = 0; e < 6; ++e) {
        CHECK((fromVoigt(&cells[0].values[6 * e]) - S).norm() < 1e-10 * S.norm());
        CHECK((fromVoigt(&cells[1].values[6 * e]) - sig).norm() < 1e-10 * sig.norm());
        CHECK(cells[2].values[e] == Approx(vm).epsilon(1e-10));
        CHECK(cells[3].values[e] == Approx(J).epsilon(1e-13));
    }
}

TEST_CASE("TLEDForceField hexahedra pass the patch test: a linear field gives constant stress and no interior force",
          "[TLEDForceField][patch]") {
    const double kappaHG = GENERATE(0.0, 0.1);
    CAPTURE(kappaHG);
    // 2x2x2 hexahedra with the centre node moved off the grid and the mid-edge nodes shifted
    Positions p = gridPoints(2, 2, 2, 0.5);
    const int centre = gridIndex(1, 1, 1, 2, 2);
    p[centre] += Vec3(0.08, -0.06, 0.05);
    p[gridIndex(1, 0, 1, 2, 2)] += Vec3(0.05, 0, -0.04);
    p[gridIndex(0, 1, 1, 2, 2)] += Vec3(0, 0.06, 0.03);
    p[gridIndex(1, 1, 0, 2, 2)] += Vec3(-0.04, 0.05, 0);
    Bench b(p);
    const auto& mat = b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
    b.forceField({}, gridHexes(2, 2, 2), {{"hourglassStiffness", std::to_string(kappaHG)}}).init();
    Mat3 A;
    A << 1.1, 0.05, 0.02, -0.03, 0.92, 0.06, 0.04, -0.01, 1.07;
    b.deform(A, Vec3(0.01, 0.02, 0.03));

    std::vector<double> S;
    b.ff->stresses(*b.state, 0, S);
    const Mat3 Sref = referenceS(mat, A);
    for (size_t e = 0; e < 8; ++e) CHECK((fromVoigt(&S[6 * e]) - Sref).norm() < 1e-10 * Sref.norm());

    const Positions f = b.forces();
    double scale = 0;
    for (auto& v : f) scale = std::max(scale, v.norm());
    CAPTURE(scale, f[centre].transpose());
    CHECK(scale > 1);
    CHECK(f[centre].norm() < 1e-10 * scale);
    // every interior face node too (nodes with 0 < i,j,k < 2 in one coordinate only are on the boundary)
    double sum = 0;
    Vec3 total = Vec3::Zero();
    for (auto& v : f) {
        total += v;
        sum += v.norm();
    }
    CHECK(total.norm() < 1e-12 * sum);  // internal forces are self-equilibrated
}

TEST_CASE("TLEDForceField hourglass control resists an hourglass mode of a hexahedron, and only with control on",
          "[TLEDForceField][hourglass]") {
    const double kappaHG = GENERATE(0.0, 0.075, 0.2);
    CAPTURE(kappaHG);
    Bench b(gridPoints(1, 1, 1, 1.0));  // unit cube, corners in VTK order
    const auto& mat = b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
    b.forceField({}, gridHexes(1, 1, 1), {{"hourglassStiffness", std::to_string(kappaHG)}}).init();
    // x-displacement along the hourglass vector xi eta: a zero-energy mode of one-point integration
    const double h1[8] = {1, -1, 1, -1, 1, -1, 1, -1};
    const double eps = 1e-3;
    const auto corner = cellCorners(0, 0, 0, 1, 1);  // local (VTK) node a -> state node
    for (int a = 0; a < 8; ++a) b.state->x()[corner[a]] = b.state->x0()[corner[a]] + Vec3(eps * h1[a], 0, 0);
    std::vector<double> S;
    b.ff->stresses(*b.state, 0, S);
    CHECK(fromVoigt(S.data()).norm() < 1e-9);  // the mode does not strain the integration point
    const Positions f = b.forces();
    // expected: f_a = -K gamma_a (gamma . u), gamma = h1 on a cube, K = kappa (lambda + 2 mu) V sum|dN|^2 / 8
    const double M = mat.bulkModulus() + 4.0 / 3.0 * mat.shearModulus();
    const double K = kappaHG * M * 1.0 * (8 * 3 / 16.0) / 8;
    double work = 0;
    for (int a = 0; a < 8; ++a) {
        CAPTURE(a);
        const Vec3& fa = f[corner[a]];
        CHECK(fa.x() == Approx(-K * h1[a] * 8 * eps).margin(1e-12));
        CHECK(std::abs(fa.y()) < 1e-12);
        CHECK(std::abs(fa.z()) < 1e-12);
        work += fa.dot(b.state->x()[corner[a]] - b.state->x0()[corner[a]]);
    }
    if (kappaHG > 0) {
        CHECK(work < 0);  // restoring
        CHECK(b.ff->potentialEnergy(*b.state) == Approx(0.5 * K * 64 * eps * eps).epsilon(1e-9));
    } else {
        for (auto& v : f) CHECK(v.norm() < 1e-12);
    }
}

TEST_CASE("TLEDForceField stable time step is L_e / c per element", "[TLEDForceField]") {
    const double mu = 1000, kappa = 20000, rho = 1100;
    const double c = std::sqrt((kappa + 4.0 / 3.0 * mu) / rho);
    SECTION("corner tetrahedron: smallest altitude 1/sqrt(3)") {
        Bench b({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        b.mass(rho);
        b.forceField({{0, 1, 2, 3}}, {}).init();
        CHECK(b.ff->stableTimeStep(*b.state) == Approx(1 / std::sqrt(3.0) / c).epsilon(1e-12));
    }
    SECTION("cuboid hexahedra: V / largest face") {
        Positions p = gridPoints(2, 1, 1, 1.0);
        for (auto& x : p) x.z() *= 0.5;  // 1 x 1 x 0.5 cells
        Bench b(p);
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        b.mass(rho);
        b.forceField({}, gridHexes(2, 1, 1)).init();
        CHECK(b.ff->stableTimeStep(*b.state) == Approx(0.5 / c).epsilon(1e-12));
        CHECK(b.ff->elementTimeStep(1, rho) == Approx(0.5 / c).epsilon(1e-12));
    }
    SECTION("the fibre stiffness raises the wave speed") {
        Bench b({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
        const auto& m = b.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "5000"}});
        b.mass(rho);
        b.forceField({{0, 1, 2, 3}}, {}).init();
        CHECK(b.ff->stableTimeStep(*b.state) == Approx(1 / std::sqrt(3.0) / m.waveSpeed(rho)).epsilon(1e-12));
        CHECK(m.waveSpeed(rho) > c);
    }
    SECTION("no mass: no limit") {
        Bench b({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        b.forceField({{0, 1, 2, 3}}, {}).init();
        CHECK(std::isinf(b.ff->stableTimeStep(*b.state)));
    }
}

TEST_CASE("TLEDForceField takes materials per mesh group and fibre directions per element from a cell array",
          "[TLEDForceField]") {
    // one hexahedron (group 1) and six tetrahedra (group 2) from a MeshData
    fascia::MeshData mesh;
    mesh.points = gridPoints(1, 1, 2, 0.1);
    mesh.hexahedra = gridHexes(1, 1, 2, 0, 1);
    mesh.tetrahedra = gridTets(1, 1, 2, 1, 2);
    mesh.hexahedronGroup = {1};
    mesh.tetrahedronGroup.assign(6, 2);
    mesh.groupNames = {{1, "muscle"}, {2, "fat"}};
    std::vector<double> fibres;
    for (int e = 0; e < 6; ++e) fibres.insert(fibres.end(), {0.0, 0.0, 2.0});  // tetrahedra first: z (normalised)
    fibres.insert(fibres.end(), {1.0, 1.0, 0.0});                           // then the hexahedron
    mesh.cellArrays["fibres"] = fibres;

    Bench b(mesh.points);
    const auto& muscle = b.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "4000"},
                                                              {"direction", "0 1 0"}}, "muscleMat");
    const auto& fat = b.material("NeoHookean", {{"mu", "300"}, {"kappa", "5000"}}, "fatMat");
    auto& ff = b.forceField({}, {});
    ff.m_mesh.set(mesh);
    const std::string mapping = GENERATE(as<std::string>{}, "1 @muscleMat 2 @fatMat", "muscle @muscleMat fat fatMat");
    CAPTURE(mapping);
    setParams(ff, {{"groupMaterials", mapping}});
    const bool useArray = GENERATE(true, false);
    if (useArray) setParams(ff, {{"fibreArray", "fibres"}});
    ff.init();
    Mat3 F;
    F << 1.1, 0.1, 0.02, 0.05, 0.93, 0.04, 0.01, 0.03, 1.02;
    b.deform(F);
    std::vector<double> S;
    ff.stresses(*b.state, 0, S);
    const Mat3 Stet = referenceS(fat, F);
    const Mat3 Shex = referenceS(muscle, F, useArray ? Vec3(1, 1, 0).normalized() : Vec3(0, 1, 0));
    for (size_t e = 0; e < 6; ++e) CHECK((fromVoigt(&S[6 * e]) - Stet).norm() < 1e-10 * Stet.norm());
    CHECK((fromVoigt(&S[36]) - Shex).norm() < 1e-10 * Shex.norm());
}

TEST_CASE("TLEDForceField rejects bad input with located messages", "[TLEDForceField]") {
    SECTION("no material") {
        Bench b(gridPoints(1, 1, 1, 1.0));
        b.forceField(gridTets(1, 1, 1), {});
        const auto msg = errorOf([&] { b.ff->init(); });
        CHECK(msg.find("scene.xml:12: error: TLEDForceField 'ff':") != std::string::npos);
        CHECK(msg.find("no material") != std::string::npos);
    }
    SECTION("no elements") {
        Bench b(gridPoints(1, 1, 1, 1.0));
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        b.forceField({}, {});
        CHECK(errorOf([&] { b.ff->init(); }).find("no elements") != std::string::npos);
    }
    SECTION("node index beyond the state") {
        Bench b({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        b.forceField({{0, 1, 2, 4}}, {});
        CHECK(errorOf([&] { b.ff->init(); }).find("node 4 but the state 'mo' has 4 nodes") != std::string::npos);
    }
    SECTION("degenerate tetrahedron") {
        Bench b({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)});
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        b.forceField({{0, 1, 2, 3}}, {});
        CHECK(errorOf([&] { b.ff->init(); }).find("tetrahedron 0 (nodes 0 1 2 3) is degenerate") != std::string::npos);
    }
    SECTION("group materials") {
        Bench b(gridPoints(1, 1, 1, 1.0));
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        auto& ff = b.forceField(gridTets(1, 1, 1), {});
        setParams(ff, {{"groupMaterials", "1 @nothing"}});
        CHECK(errorOf([&] { ff.init(); }).find("no component '@nothing'") != std::string::npos);
        setParams(ff, {{"groupMaterials", "1 @mo"}});
        CHECK(errorOf([&] { ff.init(); }).find("is a MechanicalObject, not a material") != std::string::npos);
        setParams(ff, {{"groupMaterials", "1"}});
        CHECK(errorOf([&] { ff.init(); }).find("not a list of pairs") != std::string::npos);
        setParams(ff, {{"groupMaterials", "liver @material"}});
        CHECK(errorOf([&] { ff.init(); }).find("'liver' is neither a group tag nor a group name") != std::string::npos);
    }
    SECTION("fibre array") {
        fascia::MeshData mesh;
        mesh.points = gridPoints(1, 1, 1, 1.0);
        mesh.tetrahedra = gridTets(1, 1, 1);
        mesh.cellArrays["fibres"] = std::vector<double>(9, 1.0);
        Bench b(mesh.points);
        b.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "10"}});
        auto& ff = b.forceField({}, {});
        ff.m_mesh.set(mesh);
        setParams(ff, {{"fibreArray", "fibers"}});
        const auto m1 = errorOf([&] { ff.init(); });
        CHECK(m1.find("the mesh has no such cell array") != std::string::npos);
        CHECK(m1.find("cell arrays: fibres") != std::string::npos);
        setParams(ff, {{"fibreArray", "fibres"}});
        CHECK(errorOf([&] { ff.init(); }).find("has 9 values, expected 3 per cell (18)") != std::string::npos);
    }
    SECTION("two series on the same part") {
        Bench b(gridPoints(1, 1, 1, 1.0));
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        b.prony("0.3", "1", "isochoric", "v1");
        b.prony("0.2", "2", "both", "v2");
        b.forceField(gridTets(1, 1, 1), {});
        CHECK(errorOf([&] { b.ff->init(); }).find("relax the same part") != std::string::npos);
    }
    SECTION("parameter ranges") {
        Bench b(gridPoints(1, 1, 1, 1.0));
        auto& ff = b.forceField(gridTets(1, 1, 1), {});
        CHECK_THROWS_AS(setParams(ff, {{"J0", "1.5"}}), fascia::core::Error);
        CHECK_THROWS_AS(setParams(ff, {{"hourglassStiffness", "-1"}}), fascia::core::Error);
    }
}

TEST_CASE("TLEDForceField gives bitwise identical forces for any number of threads", "[TLEDForceField][determinism]") {
    // 12^3 cells * 6 = 10368 tetrahedra and 4^3 hexahedra: several blocks
    Positions p = gridPoints(12, 12, 16, 0.01);
    Tetrahedra t = gridTets(12, 12, 16, 0, 12);
    Hexahedra h = gridHexes(12, 12, 16, 12, 16);
    Bench b(p);
    b.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "3000"}, {"direction", "1 1 1"}});
    b.prony("0.4", "0.1");
    b.forceField(t, h).init();
    b.ff->dtChanged(1e-3);
    REQUIRE(b.ff->blockCount() > 4);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1e-3, 1e-3);
    for (size_t i = 0; i < b.state->size(); ++i) b.state->x()[i] = 1.05 * b.state->x0()[i] + Vec3(u(rng), u(rng), u(rng));

    const int maxThreads = omp_get_max_threads();
    std::vector<Positions> results;
    std::vector<double> energies;
    for (int threads : {1, 2, 3}) {
        omp_set_num_threads(threads);
        // a fresh history for each run: the same two steps
        Bench c(p);
        c.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "3000"}, {"direction", "1 1 1"}});
        c.prony("0.4", "0.1");
        c.forceField(t, h).init();
        c.ff->dtChanged(1e-3);
        c.state->x() = b.state->x();
        c.forces(0.0);
        results.push_back(c.forces(1e-3));
        energies.push_back(c.ff->potentialEnergy(*c.state));
    }
    omp_set_num_threads(maxThreads);
    for (size_t r = 1; r < results.size(); ++r) {
        bool same = true;
        for (size_t i = 0; i < results[0].size(); ++i)
            for (int k = 0; k < 3; ++k) same = same && results[r][i][k] == results[0][i][k];
        CHECK(same);
        CHECK(energies[r] == energies[0]);
    }
}

TEST_CASE("TLEDForceField renumbers a poorly numbered mesh internally: same forces, stresses and energy, compact buffers",
          "[TLEDForceField][determinism]") {
    // the mixed grid of the determinism test, and the same mesh with its nodes numbered at random (among
    // half as many again: a third of the new numbers are nodes no element uses) and its elements
    // shuffled, as a mesh generator may write them: every block would then span all the nodes
    const Positions p = gridPoints(12, 12, 16, 0.01);
    const Tetrahedra t = gridTets(12, 12, 16, 0, 12);
    const Hexahedra h = gridHexes(12, 12, 16, 12, 16);
    std::mt19937 rng(7);
    std::vector<int> perm(p.size() + p.size() / 2);  // old node -> new node (the first p.size() entries)
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<size_t> tetOrder(t.size()), hexOrder(h.size());  // new element -> old element
    std::iota(tetOrder.begin(), tetOrder.end(), size_t(0));
    std::iota(hexOrder.begin(), hexOrder.end(), size_t(0));
    std::shuffle(tetOrder.begin(), tetOrder.end(), rng);
    std::shuffle(hexOrder.begin(), hexOrder.end(), rng);
    Positions ps(perm.size(), Vec3(1, 1, 1));  // the unused nodes anywhere
    for (size_t i = 0; i < p.size(); ++i) ps[static_cast<size_t>(perm[i])] = p[i];
    Tetrahedra ts;
    for (size_t e : tetOrder) ts.push_back({perm[t[e][0]], perm[t[e][1]], perm[t[e][2]], perm[t[e][3]]});
    Hexahedra hs;
    for (size_t e : hexOrder) {
        std::array<int, 8> c;
        for (int a = 0; a < 8; ++a) c[a] = perm[h[e][a]];
        hs.push_back(c);
    }
    std::uniform_real_distribution<double> u(-1e-3, 1e-3);
    Positions x(p.size());
    for (size_t i = 0; i < p.size(); ++i) x[i] = 1.05 * p[i] + Vec3(u(rng), u(rng), u(rng));

    struct Run {
        Positions f;
        std::vector<double> S;
        double energy = 0;
        size_t rows = 0;
    };
    auto run = [&](const Positions& rest, const Tetrahedra& tets, const Hexahedra& hexes, const std::vector<int>* map) {
        Bench b(rest);
        b.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "3000"}, {"direction", "1 1 1"}});
        b.prony("0.4", "0.1");
        b.forceField(tets, hexes).init();
        b.ff->dtChanged(1e-3);
        for (size_t i = 0; i < x.size(); ++i) b.state->x()[map ? static_cast<size_t>((*map)[i]) : i] = x[i];
        b.forces(0.0);
        Run r;
        r.f = b.forces(1e-3);  // a step with a viscous history
        b.ff->stresses(*b.state, 1e-3, r.S);
        r.energy = b.ff->potentialEnergy(*b.state);
        r.rows = b.ff->bufferRows();
        return r;
    };
    const Run ordered = run(p, t, h, nullptr);
    const Run scrambled = run(ps, ts, hs, &perm);
    // the ordered grid keeps its numbering: its blocks (2048 tetrahedra, 512 hexahedra, in input order)
    // span their node ranges
    size_t fileRows = 0;
    auto addRanges = [&](const auto& elements, size_t blockSize) {
        for (size_t c = 0; c < elements.size(); c += blockSize) {
            int lo = 1 << 30, hi = -1;
            for (size_t e = c; e < std::min(elements.size(), c + blockSize); ++e)
                for (int v : elements[e]) lo = std::min(lo, v), hi = std::max(hi, v);
            fileRows += static_cast<size_t>(hi - lo + 1);
        }
    };
    addRanges(t, 2048);
    addRanges(h, 512);
    CAPTURE(ordered.rows, fileRows, scrambled.rows, p.size());
    CHECK(ordered.rows == fileRows);
    CHECK(scrambled.rows < 3 * p.size());  // the file's order would need about 11 (blocks) times the node count
    bool unusedFree = true;  // the nodes no element uses get no force
    std::vector<char> isUsed(perm.size(), 0);
    for (size_t i = 0; i < p.size(); ++i) isUsed[static_cast<size_t>(perm[i])] = 1;
    for (size_t i = 0; i < perm.size(); ++i) unusedFree = unusedFree && (isUsed[i] || scrambled.f[i] == Vec3::Zero());
    CHECK(unusedFree);
    double fmax = 0, fdiff = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        fmax = std::max(fmax, ordered.f[i].norm());
        fdiff = std::max(fdiff, (scrambled.f[static_cast<size_t>(perm[i])] - ordered.f[i]).norm());
    }
    CAPTURE(fmax, fdiff);
    CHECK(fmax > 1e-3);
    CHECK(fdiff <= 1e-12 * fmax);
    // stresses in cell order: tetrahedra, then hexahedra, each in its input order
    double smax = 0, sdiff = 0;
    for (size_t c = 0; c < t.size() + h.size(); ++c) {
        const size_t old = c < t.size() ? tetOrder[c] : t.size() + hexOrder[c - t.size()];
        for (int k = 0; k < 6; ++k) {
            smax = std::max(smax, std::abs(ordered.S[6 * old + k]));
            sdiff = std::max(sdiff, std::abs(scrambled.S[6 * c + k] - ordered.S[6 * old + k]));
        }
    }
    CAPTURE(smax, sdiff);
    CHECK(smax > 1);
    CHECK(sdiff <= 1e-12 * smax);
    CHECK(scrambled.energy == Approx(ordered.energy).epsilon(1e-12));
    // renumbered, the forces are still bitwise the same for any number of threads
    const int maxThreads = omp_get_max_threads();
    omp_set_num_threads(1);
    const Run one = run(ps, ts, hs, &perm);
    omp_set_num_threads(2);
    const Run two = run(ps, ts, hs, &perm);
    omp_set_num_threads(maxThreads);
    bool same = true;
    for (size_t i = 0; i < one.f.size(); ++i) same = same && one.f[i] == two.f[i];
    CHECK(same);
}

TEST_CASE("TLEDForceField viscous history advances once per new time and repeats at the same time",
          "[TLEDForceField][viscoelastic]") {
    Bench b(gridPoints(1, 1, 1, 1.0));
    const auto& mat = b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
    b.prony("0.5", "0.2", "both");
    b.forceField({}, gridHexes(1, 1, 1)).init();
    const double dt = 0.01;
    b.ff->dtChanged(dt);
    Mat3 F = Mat3::Identity();
    F(0, 0) = 1.1;
    b.deform(F);  // a step held from t = 0
    const Mat3 Phi = referenceS(mat, F);
    const double A = dt * 0.5 / (dt + 0.2), B = 0.2 / (dt + 0.2);
    double Y = 0;
    for (int n = 0; n < 5; ++n) {
        const double t = n * dt;
        const Positions f1 = b.forces(t);
        const Positions f2 = b.forces(t);  // same time: same result
        for (int a = 0; a < 8; ++a) CHECK(f1[a] == f2[a]);
        Y = A * 1.0 + B * Y;  // Y / Phi, TLED eq. (30)
        std::vector<double> S;
        b.ff->stresses(*b.state, t, S);
        CHECK((fromVoigt(S.data()) - (1 - Y) * Phi).norm() < 1e-12 * Phi.norm());
    }
    // the elastic energy does not depend on the history
    const auto in = materials::conformance::invariantsOf(F);
    CHECK(b.ff->potentialEnergy(*b.state) == Approx(materials::conformance::evaluateOne(mat, in, 0.4).W).epsilon(1e-12));
}

TEST_CASE("TLEDForceField element loop timing (not run by default)", "[.bench][TLEDForceField]") {
    const int n = GENERATE(15, 32);  // 20k and 197k tetrahedra
    const std::string type = GENERATE(as<std::string>{}, "CompressibleNeoHookean", "NeoHookean", "TransverselyIsotropic");
    Positions p = gridPoints(n, n, n, 0.1 / n);
    Tetrahedra t = gridTets(n, n, n);
    Bench b(p);
    b.material(type, defaultParams(type));
    b.forceField(t, {}).init();
    b.deform((Mat3() << 1.02, 0.01, 0, 0, 0.99, 0.01, 0, 0, 1.0).finished());
    Positions f(b.state->size(), Vec3::Zero());
    for (int i = 0; i < 5; ++i) b.ff->addForce(*b.state, f, 0);
    std::vector<double> times;
    for (int rep = 0; rep < 7; ++rep) {
        // one thread: process CPU time (robust against a busy machine); more: wall time
        const std::clock_t c0 = std::clock();
        const double w0 = omp_get_wtime();
        for (int i = 0; i < 20; ++i) b.ff->addForce(*b.state, f, 0);
        const double sec = omp_get_max_threads() == 1 ? double(std::clock() - c0) / CLOCKS_PER_SEC : omp_get_wtime() - w0;
        times.push_back(sec / 20 / static_cast<double>(t.size()) * 1e9);
    }
    std::sort(times.begin(), times.end());
    WARN(type << " " << t.size() << " tets, " << omp_get_max_threads() << " threads: median " << times[3] << " ns/tet (min "
              << times[0] << ", max " << times[6] << ")");
}

TEST_CASE("TLEDForceField viscous paths agree: one term relaxed in the stress loop, several terms, streamed states",
          "[TLEDForceField][viscoelastic]") {
    // two terms with one tau relax like one term with the summed alpha (TLED eq. (30): A adds up, B is
    // shared), so the general path (two terms) must give the forces of the one-term path; streaming
    // the states changes only how they are stored
    // 270 tetrahedra and 18 hexahedra: full batches of 32 (streamed when on) and a partial one each
    Positions p = gridPoints(3, 3, 7, 0.01);
    const Tetrahedra t = gridTets(3, 3, 7, 0, 5);
    const Hexahedra h = gridHexes(3, 3, 7, 5, 7);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-2e-4, 2e-4);
    std::vector<Positions> xs;
    for (int n = 0; n < 4; ++n) {
        Positions x(p.size());
        for (size_t i = 0; i < p.size(); ++i) x[i] = (1.0 + 0.02 * n) * p[i] + Vec3(u(rng), u(rng), u(rng));
        xs.push_back(x);
    }
    const std::string apply = GENERATE(as<std::string>{}, "isochoric", "volumetric", "both");
    CAPTURE(apply);
    auto run = [&](const std::string& alpha, const std::string& tau, const std::string& stream) {
        Bench b(p);
        b.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "3000"}, {"direction", "0 1 1"}});
        b.prony(alpha, tau, apply);
        b.forceField(t, h, {{"streamStates", stream}}).init();
        b.ff->dtChanged(1e-3);
        std::vector<Positions> out;
        for (int n = 0; n < 4; ++n) {
            b.state->x() = xs[size_t(n)];
            out.push_back(b.forces(n * 1e-3));
        }
        std::vector<double> S;
        b.ff->stresses(*b.state, 3e-3, S);
        return std::make_pair(out, S);
    };
    const auto one = run("0.5", "0.01", "off");
    const auto two = run("0.2 0.3", "0.01 0.01", "off");
    const auto streamed = run("0.5", "0.01", "on");
    const auto twoStreamed = run("0.2 0.3", "0.01 0.01", "on");
    double scale = 0, diff = 0;
    for (int n = 0; n < 4; ++n)
        for (size_t i = 0; i < p.size(); ++i) {
            scale = std::max(scale, one.first[size_t(n)][i].norm());
            diff = std::max(diff, (two.first[size_t(n)][i] - one.first[size_t(n)][i]).norm());
            CHECK(streamed.first[size_t(n)][i] == one.first[size_t(n)][i]);
            CHECK(twoStreamed.first[size_t(n)][i] == two.first[size_t(n)][i]);
        }
    REQUIRE(scale > 0);
    CHECK(diff < 1e-12 * scale);
    // the stresses reported for the last step follow the same history
    double sScale = 0, sDiff = 0;
    for (size_t i = 0; i < one.second.size(); ++i) {
        sScale = std::max(sScale, std::abs(one.second[i]));
        sDiff = std::max(sDiff, std::abs(two.second[i] - one.second[i]));
    }
    CHECK(sDiff < 1e-12 * sScale);
}

TEST_CASE("TLEDForceField viscous states stay with their elements across blocks and batches",
          "[TLEDForceField][viscoelastic]") {
    // a non-uniform deformation held from t = 0 on 6 blocks of tetrahedra and 2 of hexahedra (full and
    // partial batches): with apply="both" every element's S must be (1 - y_n) Phi_e, y_n = A + B y_(n-1)
    // (TLED eq. (30)), Phi_e its own elastic stress (from the same force field without relaxation);
    // a state read or written in another element's slot would mix two different Phi
    const Positions p = gridPoints(12, 12, 16, 0.01);
    Positions x = p;
    for (auto& q : x) q += 0.004 * Vec3(std::sin(40 * q[1]), std::sin(30 * q[2]), std::sin(50 * q[0]));
    auto make = [&](Bench& b, bool visco) {
        b.material("NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}});
        if (visco) b.prony("0.5", "0.02", "both");
        b.forceField(gridTets(12, 12, 16, 0, 12), gridHexes(12, 12, 16, 12, 16)).init();
        b.state->x() = x;
    };
    Bench b(p), elastic(p);
    make(b, true);
    make(elastic, false);
    REQUIRE(b.ff->blockCount() == 8);
    const double dt = 0.01;
    b.ff->dtChanged(dt);
    std::vector<double> Phi;
    elastic.ff->stresses(*elastic.state, 0, Phi);
    double scale = 0;
    for (double v : Phi) scale = std::max(scale, std::abs(v));
    const double A = dt * 0.5 / (dt + 0.02), B = 0.02 / (dt + 0.02);
    double y = 0;
    for (int n = 0; n < 4; ++n) {
        b.forces(n * dt);
        y = A + B * y;
        std::vector<double> S;
        b.ff->stresses(*b.state, n * dt, S);
        REQUIRE(S.size() == Phi.size());
        double worst = 0;
        for (size_t i = 0; i < S.size(); ++i) worst = std::max(worst, std::abs(S[i] - (1 - y) * Phi[i]));
        CHECK(worst < 1e-11 * scale);
    }
}

TEST_CASE("TLEDForceField fibre directions per group and per element give the same forces",
          "[TLEDForceField]") {
    // two groups of tetrahedra or of hexahedra with different material directions: the vectorised
    // loop reads them per group (no array) or per element (a cell array holding the same directions;
    // for hexahedra its rows come after the hourglass vectors in the packed element data)
    const bool hexes = GENERATE(false, true);
    CAPTURE(hexes);
    fascia::MeshData mesh;
    mesh.points = gridPoints(6, 6, 8, 0.01);
    if (hexes) mesh.hexahedra = gridHexes(6, 6, 8);
    else mesh.tetrahedra = gridTets(6, 6, 8);
    const size_t nt = hexes ? mesh.hexahedra.size() : mesh.tetrahedra.size();
    std::vector<int>& groups = hexes ? mesh.hexahedronGroup : mesh.tetrahedronGroup;
    groups.resize(nt);
    std::vector<double> fibres;
    for (size_t e = 0; e < nt; ++e) {
        const bool upper = e >= nt / 2;
        groups[e] = upper ? 2 : 1;
        if (upper) fibres.insert(fibres.end(), {1.0, 0.0, 1.0});
        else fibres.insert(fibres.end(), {0.0, 1.0, 0.0});
    }
    mesh.cellArrays["fibres"] = fibres;
    Positions x = mesh.points;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-3e-4, 3e-4);
    for (auto& q : x) q = 1.03 * q + Vec3(u(rng), u(rng), u(rng));
    auto run = [&](bool array) {
        Bench b(mesh.points);
        b.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "4000"}, {"direction", "0 1 0"}}, "m1");
        b.material("TransverselyIsotropic", {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "4000"}, {"direction", "1 0 1"}}, "m2");
        auto& ff = b.forceField({}, {});
        ff.m_mesh.set(mesh);
        setParams(ff, {{"groupMaterials", "1 @m1 2 @m2"}});
        if (array) setParams(ff, {{"fibreArray", "fibres"}});
        ff.init();
        b.state->x() = x;
        return b.forces();
    };
    const NodalDifference d = nodalDifference(run(true), run(false));
    REQUIRE(d.scale > 0);
    CHECK(d.diff <= 1e-14 * d.scale);
}

TEST_CASE("TLEDForceField forces do not depend on how groups split the elements into blocks and batches",
          "[TLEDForceField]") {
    // a mixed mesh (hexahedra below, tetrahedra above) with per-element fibres. Once with one material,
    // once with two identical materials assigned to groups that cut the elements at boundaries which
    // are not multiples of the batch size: the element data of each batch (dN, hourglass vectors,
    // fibres) must follow its elements through the different internal order
    fascia::MeshData mesh;
    mesh.points = gridPoints(7, 6, 10, 0.01);
    mesh.hexahedra = gridHexes(7, 6, 10, 0, 5);
    mesh.tetrahedra = gridTets(7, 6, 10, 5, 10);
    const size_t nh = mesh.hexahedra.size(), nt = mesh.tetrahedra.size();
    REQUIRE(nh > 64);
    REQUIRE(nt > 1000);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> fibres;
    for (size_t e = 0; e < nt + nh; ++e) fibres.insert(fibres.end(), {u(rng), u(rng), 1.5 + u(rng)});
    mesh.cellArrays["fibres"] = fibres;
    mesh.tetrahedronGroup.resize(nt);
    mesh.hexahedronGroup.resize(nh);
    for (size_t e = 0; e < nt; ++e) mesh.tetrahedronGroup[e] = (e % 7 == 3 || (e > 333 && e < 700)) ? 2 : 1;
    for (size_t e = 0; e < nh; ++e) mesh.hexahedronGroup[e] = (e % 5 == 1 || e > 101) ? 2 : 1;
    Positions x = mesh.points;
    std::uniform_real_distribution<double> d(-3e-4, 3e-4);
    for (auto& q : x) q = 1.02 * q + Vec3(d(rng), d(rng), d(rng));
    auto run = [&](bool split) {
        Bench b(mesh.points);
        const ParamList p = {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "4000"}, {"direction", "0 1 0"}};
        b.material("TransverselyIsotropic", p, "m1");
        b.material("TransverselyIsotropic", p, "m2");
        auto& ff = b.forceField({}, {});
        ff.m_mesh.set(mesh);
        setParams(ff, {{"groupMaterials", split ? "1 @m1 2 @m2" : "1 @m1 2 @m1"}, {"fibreArray", "fibres"}});
        ff.init();
        b.state->x() = x;
        return b.forces();
    };
    const NodalDifference split = nodalDifference(run(false), run(true));
    REQUIRE(split.scale > 0);
    CHECK(split.diff <= 1e-12 * split.scale);
}
