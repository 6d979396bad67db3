// HEMLForceField against references that share no code with it or with the materials plugin's law
// code (plugins/materials/tests/LawReference.h): direct finite elements f_a = -V P dN_a/dX with
// P = dW/dF of each law's paper energy written from F. Every law on a single tetrahedron (including
// a crushed one below J0, and a non-default J0), fibre directions off the axes per material, per
// group and per element (fibreArray and fibreArray2), and the viscous forces of a held deformation.
#include "../../materials/tests/LawReference.h"
#include "HEMLTestSupport.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace fascia;
using namespace hemltest;

namespace {

/// Adds a material of the materials plugin described by an independent LawSpec (not initialised).
materials::BaseMaterial& addLaw(core::Node& n, const lawref::LawSpec& s, const std::string& name) {
    using namespace materials;
    BaseMaterial* m = nullptr;
    if (s.type == "StVenantKirchhoff") m = &n.add<StVenantKirchhoff>(name);
    else if (s.type == "IncompressibleNeoHookean") m = &n.add<IncompressibleNeoHookean>(name);
    else if (s.type == "IncompressibleMooneyRivlin") m = &n.add<IncompressibleMooneyRivlin>(name);
    else if (s.type == "CompressibleNeoHookean") m = &n.add<CompressibleNeoHookean>(name);
    else if (s.type == "CompressibleMooneyRivlin") m = &n.add<CompressibleMooneyRivlin>(name);
    else if (s.type == "NeoHookean") m = &n.add<NeoHookean>(name);
    else if (s.type == "TransverselyIsotropic") m = &n.add<TransverselyIsotropic>(name);
    else m = &n.add<Orthotropic>(name);
    for (const auto& [k, v] : s.params()) m->findParam(k)->read(v, {});
    return *m;
}

/// One tetrahedron of no particular shape (edges of different lengths, no right angle).
MeshData oneTet() {
    MeshData m;
    m.points = {Vec3(0.001, -0.002, 0.0), Vec3(0.013, 0.001, -0.002), Vec3(0.002, 0.011, 0.001), Vec3(-0.001, 0.003, 0.012)};
    m.tetrahedra = {{0, 1, 2, 3}};
    return m;
}

/// x = A X + c for a homogeneous deformation A (with a rotation part), plus an optional jitter.
Positions mapped(const Positions& X, const Mat3& A, double jitter = 0, unsigned seed = 4) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    Positions x(X.size());
    for (size_t i = 0; i < X.size(); ++i) x[i] = A * X[i] + Vec3(0.002, -0.001, 0.003) + jitter * Vec3(u(rng), u(rng), u(rng));
    return x;
}

// homogeneous deformations: general (J ~ 1.19), compressive (J ~ 0.49), large (J ~ 2.9),
// crushed below J0 = 0.4 (J ~ 0.2), inverted (J ~ -0.29)
Mat3 deformation(int k) {
    switch (k) {
    case 0: return (Mat3() << 1.2, 0.1, 0.0, -0.05, 0.9, 0.2, 0.03, 0.0, 1.1).finished();
    case 1: return (Mat3() << 0.8, 0.3, 0.1, 0.0, 0.7, -0.1, 0.2, 0.05, 0.9).finished();
    case 2: return (Mat3() << 1.6, 0.0, 0.3, 0.4, 1.3, 0.0, 0.0, -0.2, 1.4).finished();
    case 3: return (Mat3() << 0.6, 0.1, 0.0, 0.0, 0.55, 0.05, 0.0, 0.0, 0.6).finished();
    default: return (Mat3() << 0.9, 0.1, 0.0, 0.0, 0.8, 0.1, 0.05, 0.0, -0.4).finished();
    }
}

} // namespace

TEST_CASE("HEML forces on one tetrahedron equal direct FE with P = dW/dF of every law's paper energy",
          "[HEMLForceField]") {
    const auto laws = lawref::allLaws();
    const size_t li = GENERATE(range(size_t(0), size_t(8)));
    const int k = GENERATE(range(0, 5));
    const lawref::LawSpec& spec = laws[li];
    const MeshData mesh = oneTet();
    Scene s(mesh);
    addLaw(s.root, spec, "mat");
    s.init();
    s.state->x() = mapped(mesh.points, deformation(k));
    const Positions f = s.forces();
    const Positions ref = lawref::tetForces(mesh.points, mesh.tetrahedra, s.state->x(), [&](size_t) { return spec; });
    CAPTURE(spec.type, k, deformation(k).determinant());
    CHECK(maxNorm(ref) > 1e-3);
    CHECK(lawref::relativeDifference(f, ref) < 1e-9);
    // the energy is Vol W
    const double vol = std::abs((mesh.points[1] - mesh.points[0]).dot((mesh.points[2] - mesh.points[0]).cross(mesh.points[3] - mesh.points[0]))) / 6;
    CHECK(s.ff->potentialEnergy(*s.state) == Approx(vol * lawref::energy(spec, deformation(k))).epsilon(1e-11));
}

TEST_CASE("HEML takes a non-default J0: a crushed tetrahedron follows the tangent continuation at that J0",
          "[HEMLForceField]") {
    const std::string type = GENERATE("NeoHookean", "CompressibleNeoHookean", "TransverselyIsotropic", "CompressibleMooneyRivlin");
    const lawref::LawSpec spec = lawref::lawNamed(type);
    const MeshData mesh = oneTet();
    Scene s(mesh);
    addLaw(s.root, spec, "mat");
    s.ff->m_J0.set(0.7);
    s.init();
    // J = 0.55: above the default J0 = 0.4, below 0.7
    const Mat3 A = (Mat3() << 0.82, 0.1, 0.0, 0.0, 0.8, 0.05, 0.02, 0.0, 0.84).finished();
    REQUIRE(A.determinant() == Approx(0.55).margin(0.01));
    s.state->x() = mapped(mesh.points, A);
    const Positions f = s.forces();
    auto law = [&](size_t) { return spec; };
    const Positions at07 = lawref::tetForces(mesh.points, mesh.tetrahedra, s.state->x(), law, 0.7);
    const Positions at04 = lawref::tetForces(mesh.points, mesh.tetrahedra, s.state->x(), law, 0.4);
    CAPTURE(type);
    CHECK(lawref::relativeDifference(f, at07) < 1e-9);
    CHECK(lawref::relativeDifference(at04, at07) > 1e-3);  // the parameter matters here
}

TEST_CASE("HEML fibre terms with off-axis directions per element from fibreArray and fibreArray2 equal direct FE",
          "[HEMLForceField]") {
    const std::string type = GENERATE("TransverselyIsotropic", "Orthotropic");
    const MeshData base = cubeMesh(2, 2, 2);
    MeshData mesh = base;
    std::vector<double> a, b;
    lawref::elementFibres(mesh.tetrahedra.size(), a, b);
    mesh.cellArrays["fibres"] = a;
    mesh.cellArrays["fibres2"] = b;
    lawref::LawSpec spec = lawref::lawNamed(type);
    Scene s(mesh);
    addLaw(s.root, spec, "mat");
    s.ff->m_fibreArray.set("fibres");
    if (spec.hasFibre2()) s.ff->m_fibreArray2.set("fibres2");
    s.init();
    s.state->x() = mapped(mesh.points, deformation(0), 0.0005);
    const Positions f = s.forces();
    auto lawOf = [&](size_t e) {
        lawref::LawSpec l = spec;
        l.a0 = lawref::fibreOf(a, e);
        l.b0 = lawref::fibreOf(b, e);
        return l;
    };
    const Positions ref = lawref::tetForces(mesh.points, mesh.tetrahedra, s.state->x(), lawOf);
    // the material's own directions would give other forces: the arrays are what is used
    const Positions matDirs = lawref::tetForces(mesh.points, mesh.tetrahedra, s.state->x(), [&](size_t) { return spec; });
    CAPTURE(type);
    CHECK(lawref::relativeDifference(f, ref) < 1e-9);
    CHECK(lawref::relativeDifference(matDirs, ref) > 1e-3);
}

TEST_CASE("HEML fibre terms with off-axis directions per group equal direct FE", "[HEMLForceField]") {
    const std::string type = GENERATE("TransverselyIsotropic", "Orthotropic");
    const MeshData mesh = cubeMesh(4, 2, 2);  // groups 1 (left) and 2 (right)
    lawref::LawSpec s1 = lawref::lawNamed(type), s2 = s1;
    s2.a0 = Vec3(-2, 1, 0.5);
    s2.b0 = Vec3(1, 2, 0);  // orthogonal to a0
    s2.eta = 4500;
    Scene s(mesh);
    addLaw(s.root, s1, "m1");
    addLaw(s.root, s2, "m2");
    s.ff->m_groupMaterials.set("left @m1 right @m2");
    s.init();
    s.state->x() = mapped(mesh.points, deformation(1), 0.0005);
    const Positions f = s.forces();
    const Positions ref = lawref::tetForces(mesh.points, mesh.tetrahedra, s.state->x(),
                                            [&](size_t e) { return mesh.tetrahedronGroup[e] == 1 ? s1 : s2; });
    CAPTURE(type);
    CHECK(lawref::relativeDifference(f, ref) < 1e-9);
}

TEST_CASE("HEML viscous forces of a held deformation with off-axis fibres relax the isochoric part by HEML eq. (20)",
          "[HEMLForceField]") {
    // a deformation held from step 1: gamma^n = alpha (1 - B^n) f_relaxed (eq. (20) with a constant f),
    // so f^n = f - alpha (1 - B^n) f_relaxed, f_relaxed the isochoric part (apply="isochoric") or all
    // of f (apply="both"), each part computed by direct FE from the reference energy's parts
    const std::string type = GENERATE("TransverselyIsotropic", "Orthotropic");
    const std::string apply = GENERATE("isochoric", "both");
    MeshData mesh = cubeMesh(2, 2, 2);
    std::vector<double> a, b;
    lawref::elementFibres(mesh.tetrahedra.size(), a, b);
    mesh.cellArrays["fibres"] = a;
    mesh.cellArrays["fibres2"] = b;
    const lawref::LawSpec spec = lawref::lawNamed(type);
    const double alpha = 0.4, tau = 0.05, dt = 0.01, B = tau / (dt + tau);
    Scene s(mesh);
    addLaw(s.root, spec, "mat");
    auto& visco = s.root.add<viscoelastic::ViscoelasticProny>("visco");
    visco.findParam("alpha")->read("0.4", {});
    visco.findParam("tau")->read("0.05", {});
    visco.findParam("apply")->read(apply, {});
    s.ff->m_fibreArray.set("fibres");
    if (spec.hasFibre2()) s.ff->m_fibreArray2.set("fibres2");
    s.init();
    visco.setTimeStep(dt);
    // a deformation with a volume change, so that the two parts differ
    s.state->x() = mapped(mesh.points, 1.04 * deformation(0), 0.0005);
    auto lawOf = [&](size_t e) {
        lawref::LawSpec l = spec;
        l.a0 = lawref::fibreOf(a, e);
        l.b0 = lawref::fibreOf(b, e);
        return l;
    };
    const Positions& x = s.state->x();
    const Positions fIso = lawref::tetForces(mesh.points, mesh.tetrahedra, x, lawOf, 0.4, lawref::Part::Isochoric);
    const Positions fVol = lawref::tetForces(mesh.points, mesh.tetrahedra, x, lawOf, 0.4, lawref::Part::Volumetric);
    REQUIRE(maxNorm(fVol) > 0.1 * maxNorm(fIso));
    CAPTURE(type, apply);
    for (int n = 1; n <= 6; ++n) {
        const Positions f = s.forces(n * dt);
        const double y = alpha * (1 - std::pow(B, n));
        Positions ref(f.size());
        for (size_t i = 0; i < f.size(); ++i)
            ref[i] = apply == "both" ? Vec3((1 - y) * (fIso[i] + fVol[i])) : Vec3((1 - y) * fIso[i] + fVol[i]);
        CAPTURE(n);
        CHECK(lawref::relativeDifference(f, ref) < 1e-9);
    }
}
