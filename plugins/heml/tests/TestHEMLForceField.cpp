// HEMLForceField: conformance harness on every material, equality with a direct FE computation,
// mass-spring degenerate case (HEML section 5.3), flat/inverted elements (section 4.4),
// determinism across thread counts, viscoelasticity (section 3.5), parameters.
#include "HEMLTestSupport.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"
#include "fascia/materials/Conformance.h"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <map>
#include <omp.h>

using namespace fascia;
using namespace hemltest;
namespace conf = fascia::materials::conformance;

namespace {

// f_i = -Vol P grad N_i with P = F S, S from the law's invariant derivatives (Material.h), per element
Positions directFE(const MeshData& mesh, const Positions& x, const heml::HEMLForceField& ff, double J0) {
    Positions f(x.size(), Vec3::Zero());
    for (size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
        const auto& t = mesh.tetrahedra[e];
        Mat3 V, v;
        for (int k = 0; k < 3; ++k) {
            V.col(k) = mesh.points[t[k + 1]] - mesh.points[t[0]];
            v.col(k) = x[t[k + 1]] - x[t[0]];
        }
        const Mat3 Vi = V.inverse();
        const Mat3 F = v * Vi;
        const double vol = std::abs(V.determinant()) / 6;
        const materials::BaseMaterial* m = ff.materialOf(e);
        const Vec3 a = m->fibreDirection(0) ? *m->fibreDirection(0) : Vec3(0, 0, 1);
        const Vec3 b = m->fibreDirection(1) ? *m->fibreDirection(1) : Vec3(1, 0, 0);
        const Mat3 C = F.transpose() * F;
        const auto in = conf::invariantsOf(F, a, b);
        const auto r = conf::evaluateOne(*m, in, J0);
        const Mat3 S = 2 * (r.dI1 * Mat3::Identity() + r.dI2 * (in.I1 * Mat3::Identity() - C) +
                            r.dI4 * a * a.transpose() + r.dI6 * b * b.transpose()) +
                       in.J * (r.dJiso + r.dJvol) * C.inverse();
        const Mat3 P = F * S;
        Vec3 g0 = Vec3::Zero();
        for (int k = 0; k < 3; ++k) {
            const Vec3 gk = Vi.row(k).transpose();
            f[t[k + 1]] -= vol * P * gk;
            g0 -= gk;
        }
        f[t[0]] -= vol * P * g0;
    }
    return f;
}

Positions deformed(const Positions& X, double amp, unsigned seed = 3) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const Mat3 A = (Mat3() << 1.1, 0.08, -0.02, 0.03, 0.92, 0.05, -0.04, 0.02, 1.04).finished();
    Positions x(X.size());
    for (size_t i = 0; i < X.size(); ++i) x[i] = A * X[i] + amp * Vec3(u(rng), u(rng), u(rng));
    return x;
}

// a material that is not a Material<Law>: the force field runs its generic loop for it
using Wrapped = materials::conformance::GenericMaterial;

} // namespace

TEST_CASE("every material passes the conformance harness through HEMLForceField", "[HEMLForceField]") {
    const std::string name = GENERATE(from_range(kMaterials));
    const bool generic = GENERATE(false, true);
    const MeshData mesh = cubeMesh(3, 2, 2);
    Scene s(mesh);
    auto& mat = addMaterial(s.root, name, "mat");
    if (generic) {
        mat.init();
        auto& w = s.root.add<Wrapped>("wrapped");
        w.inner = &mat;
        s.ff->m_material.set(&w);
    }
    s.init();
    CHECK(s.ff->usesFastPath() == !generic);
    const auto rep = conf::checkForceField(*s.ff, *s.state);
    INFO(name << (generic ? " (generic path)" : "") << ": gradient " << rep.gradientError << " rest " << rep.restForce
              << " rotation " << rep.rotationError << " energy rotation " << rep.energyRotationError);
    CHECK(rep.forceScale > 0);
    CHECK(rep.gradientError < 1e-7);
    CHECK(rep.rotationError < 1e-10);
    CHECK(rep.energyRotationError < 1e-10);
    if (mat.stressFreeAtRest()) CHECK(rep.restForce < 1e-10);
    else CHECK(rep.restForce > 1e-3);  // HEML Table 3 "incompressible" laws: S = 2 (C1 + 2 C2) I at rest
}

TEST_CASE("HEML forces equal a direct finite-element computation f = -Vol P grad N", "[HEMLForceField]") {
    const std::string name = GENERATE(from_range(kMaterials));
    const MeshData mesh = cubeMesh(3, 3, 2);
    Scene s(mesh);
    addMaterial(s.root, name, "mat");
    s.init();
    s.state->x() = deformed(mesh.points, 0.002);
    const Positions f = s.forces();
    const Positions ref = directFE(mesh, s.state->x(), *s.ff, 0.4);
    double err = 0;
    for (size_t i = 0; i < f.size(); ++i) err = std::max(err, (f[i] - ref[i]).norm());
    INFO(name << ": max |f - f_FE| / max |f_FE| = " << err / maxNorm(ref));
    CHECK(err < 1e-10 * maxNorm(ref));
}

// HEML Algorithm 1 and 2 written literally: C_k = V^-T D_k V^-1 (A.6), vtr, Mtr (C.1), dW/dl from
// (C.2)-(C.3), dl/dx_i = DLM_i v (B.1)-(B.2), the J term through dvol/dx_i (C.4), eq. (29)
Positions paperAlgorithm(const MeshData& mesh, const Positions& x, const heml::HEMLForceField& ff, double J0) {
    Mat3 D[6];
    D[0] << 1, 0.5, 0.5, 0.5, 0, 0, 0.5, 0, 0;
    D[1] << 0, 0.5, 0, 0.5, 1, 0.5, 0, 0.5, 0;
    D[2] << 0, 0, 0.5, 0, 0, 0.5, 0.5, 0.5, 1;
    D[3] << 0, -0.5, 0, -0.5, 0, 0, 0, 0, 0;
    D[4] << 0, 0, 0, 0, 0, -0.5, 0, -0.5, 0;
    D[5] << 0, 0, -0.5, 0, 0, 0, -0.5, 0, 0;
    Eigen::Matrix<double, 6, 3> DLM[4];
    DLM[0] << -2, 0, 0, 0, -2, 0, 0, 0, -2, 0, 0, 0, 0, 0, 0, 0, 0, 0;
    DLM[1] << 2, 0, 0, 0, 0, 0, 0, 0, 0, 2, -2, 0, 0, 0, 0, 2, 0, -2;
    DLM[2] << 0, 0, 0, 0, 2, 0, 0, 0, 0, -2, 2, 0, 0, 2, -2, 0, 0, 0;
    DLM[3] << 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, -2, 2, -2, 0, 2;
    using Vec6 = Eigen::Matrix<double, 6, 1>;
    Positions f(x.size(), Vec3::Zero());
    for (size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
        const auto& t = mesh.tetrahedra[e];
        Mat3 V, v;
        for (int k = 0; k < 3; ++k) {
            V.col(k) = mesh.points[t[k + 1]] - mesh.points[t[0]];
            v.col(k) = x[t[k + 1]] - x[t[0]];
        }
        const Mat3 Vi = V.inverse();
        const double Vol = std::abs(V.determinant()) / 6;
        Mat3 C[6];
        Vec6 vtr, a4;
        Eigen::Matrix<double, 6, 6> Mtr;
        const materials::BaseMaterial* m = ff.materialOf(e);
        const Vec3 a0 = m->fibreDirection(0) ? *m->fibreDirection(0) : Vec3(0, 0, 1);
        for (int k = 0; k < 6; ++k) {
            C[k] = Vi.transpose() * D[k] * Vi;
            vtr[k] = C[k].trace();
            a4[k] = a0.dot(C[k] * a0);
        }
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j) Mtr(i, j) = (C[i] * C[j]).trace();
        const Vec3 ed[6] = {v.col(0), v.col(1), v.col(2), v.col(1) - v.col(0), v.col(2) - v.col(1), v.col(0) - v.col(2)};
        Vec6 l;
        for (int k = 0; k < 6; ++k) l[k] = ed[k].squaredNorm();
        materials::Invariants in;
        in.I1 = vtr.dot(l);
        in.I2 = 0.5 * l.dot((vtr * vtr.transpose() - Mtr) * l);
        in.J = v.determinant() / V.determinant();
        in.I4 = a4.dot(l);
        REQUIRE((m->uses() & materials::BaseMaterial::UsesI6) == 0u);
        const auto r = conf::evaluateOne(*m, in, J0);
        const Vec6 dWdl = r.dI1 * vtr + r.dI2 * (vtr * vtr.transpose() - Mtr) * l + r.dI4 * a4;
        const double dWdJ = r.dJiso + r.dJvol;
        // dvol/dx_i (C.4), vol = det(v)/6, J = vol / (det V / 6)
        const Vec3 dv1 = v.col(1).cross(v.col(2)) / 6, dv2 = v.col(2).cross(v.col(0)) / 6, dv3 = v.col(0).cross(v.col(1)) / 6;
        const Vec3 dvol[4] = {-(dv1 + dv2 + dv3), dv1, dv2, dv3};
        for (int i = 0; i < 4; ++i) {
            const Eigen::Matrix<double, 6, 3> dl = DLM[i] * v.transpose();  // rows: dl_k/dx_i (B.1)
            f[t[i]] -= Vol * (dl.transpose() * dWdl) + Vol * dWdJ * (6.0 / V.determinant()) * dvol[i];
        }
    }
    return f;
}

TEST_CASE("the fast loop equals HEML Algorithm 2 written literally with vtr, Mtr and DLM", "[HEMLForceField]") {
    const std::string name = GENERATE("StVenantKirchhoff", "IncompressibleMooneyRivlin", "CompressibleNeoHookean",
                                      "CompressibleMooneyRivlin", "TransverselyIsotropic");
    const MeshData mesh = cubeMesh(3, 2, 2);
    Scene s(mesh);
    addMaterial(s.root, name, "mat");
    s.init();
    s.state->x() = deformed(mesh.points, 0.002);
    const Positions f = s.forces(), ref = paperAlgorithm(mesh, s.state->x(), *s.ff, 0.4);
    double err = 0;
    for (size_t i = 0; i < f.size(); ++i) err = std::max(err, (f[i] - ref[i]).norm());
    INFO(name << ": " << err / maxNorm(ref));
    CHECK(err < 1e-10 * maxNorm(ref));
}

TEST_CASE("per group materials from a mesh's group tags or names", "[HEMLForceField]") {
    const MeshData mesh = cubeMesh(4, 2, 2);
    Scene s(mesh);
    addMaterial(s.root, "NeoHookean", "soft");
    addMaterial(s.root, "TransverselyIsotropic", "fibrous");
    const std::string spec = GENERATE(std::string("1 @soft 2 @fibrous"), std::string("left @soft right @fibrous"));
    s.ff->m_groupMaterials.set(spec);
    s.init();
    size_t nSoft = 0;
    for (size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
        CHECK(s.ff->materialOf(e)->name() == (mesh.tetrahedronGroup[e] == 1 ? "soft" : "fibrous"));
        nSoft += s.ff->materialOf(e)->name() == "soft";
    }
    CHECK(nSoft == mesh.tetrahedra.size() / 2);
    s.state->x() = deformed(mesh.points, 0.002);
    const Positions f = s.forces(), ref = directFE(mesh, s.state->x(), *s.ff, 0.4);
    double err = 0;
    for (size_t i = 0; i < f.size(); ++i) err = std::max(err, (f[i] - ref[i]).norm());
    CHECK(err < 1e-10 * maxNorm(ref));
}

TEST_CASE("mass-spring mode gives the classical spring forces (HEML eq. (36) = eq. (41))", "[HEMLForceField]") {
    const MeshData mesh = cubeMesh(3, 2, 2);
    Scene s(mesh);
    const double k = 150.0;
    s.ff->m_stiffness.set(k);
    s.init();
    s.state->x() = deformed(mesh.points, 0.002);
    const Positions& x = s.state->x();
    const Positions f = s.forces();
    // classical springs, one per unique edge: f_a = k (l - l0)/l (x_b - x_a)   (eq. (35))
    std::map<std::pair<int, int>, bool> edges;
    for (const auto& t : mesh.tetrahedra)
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) edges[{std::min(t[a], t[b]), std::max(t[a], t[b])}] = true;
    Positions ref(x.size(), Vec3::Zero());
    double E = 0;
    for (const auto& [e, _] : edges) {
        const Vec3 v = x[e.second] - x[e.first];
        const double l = v.norm(), l0 = (mesh.points[e.second] - mesh.points[e.first]).norm();
        ref[e.first] += k * (l - l0) / l * v;
        ref[e.second] -= k * (l - l0) / l * v;
        E += 0.5 * k * (l - l0) * (l - l0);
    }
    double err = 0;
    for (size_t i = 0; i < f.size(); ++i) err = std::max(err, (f[i] - ref[i]).norm());
    CHECK(err < 1e-13 * maxNorm(ref));
    CHECK(s.ff->potentialEnergy(*s.state) == Approx(E).epsilon(1e-12));
    const auto rep = conf::checkForceField(*s.ff, *s.state);
    CHECK(rep.gradientError < 1e-7);
    CHECK(rep.restForce < 1e-12);
    CHECK(rep.rotationError < 1e-10);
}

TEST_CASE("an element crushed through J = 0 into inversion has finite forces pushing it back", "[HEMLForceField]") {
    const std::string name = GENERATE("CompressibleNeoHookean", "NeoHookean", "CompressibleMooneyRivlin", "TransverselyIsotropic");
    MeshData mesh;
    mesh.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    mesh.tetrahedra = {{0, 1, 2, 3}};
    Scene s(mesh);
    addMaterial(s.root, name, "mat");
    s.init();
    double prev = 0;
    for (double z : {0.5, 0.4, 0.3, 0.1, 0.0, -0.1, -0.3}) {
        s.state->x()[3] = Vec3(0.1, 0.1, z);  // J = z
        const Positions f = s.forces();
        const auto cells = [&] {
            std::vector<core::CellField> c;
            s.ff->cellData(*s.state, c);
            return c;
        }();
        CAPTURE(name, z, f[3].transpose());
        CHECK(std::isfinite(f[3].squaredNorm() + f[0].squaredNorm() + f[1].squaredNorm() + f[2].squaredNorm()));
        CHECK(f[3].z() > 0);  // pushed back up, through the face and out of inversion
        // below J0 the volumetric tangent makes it harder the deeper it goes (for split laws the
        // isochoric J derivative is dropped at J0, so the force may step down once there)
        if (z < 0.4) CHECK(f[3].z() > prev);
        prev = z < 0.4 ? f[3].z() : 0.0;
        CHECK(cells[0].values[0] == Approx(z).margin(1e-15));  // J
        CHECK(std::isfinite(cells[1].values[0]));              // von Mises
        CHECK(std::isfinite(s.ff->potentialEnergy(*s.state)));
    }
}

TEST_CASE("forces are bitwise identical with 1 and 2 threads", "[HEMLForceField]") {
    const std::string name = GENERATE("NeoHookean", "TransverselyIsotropic", "springs");
    const MeshData mesh = cubeMesh(9, 8, 8, 0.01, 0.15, 11);  // 3456 tetrahedra: several blocks
    Scene s(mesh);
    if (name == "springs") s.ff->m_stiffness.set(10.0);
    else addMaterial(s.root, name, "mat");
    s.init();
    REQUIRE(s.ff->blockCount() >= 3);
    s.state->x() = deformed(mesh.points, 0.001);
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const Positions f1 = s.forces();
    const double e1 = s.ff->potentialEnergy(*s.state);
    omp_set_num_threads(2);
    const Positions f2 = s.forces();
    const double e2 = s.ff->potentialEnergy(*s.state);
    omp_set_num_threads(saved);
    CHECK(std::memcmp(f1.data(), f2.data(), f1.size() * sizeof(Vec3)) == 0);
    CHECK(std::memcmp(&e1, &e2, sizeof e1) == 0);
}

TEST_CASE("the internal node renumbering leaves the state's node order unchanged", "[HEMLForceField]") {
    const MeshData mesh = cubeMesh(5, 4, 3);
    // the same mesh with its nodes shuffled
    std::vector<int> perm(mesh.points.size());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), std::mt19937(5));
    MeshData shuffled = mesh;
    for (size_t i = 0; i < perm.size(); ++i) shuffled.points[perm[i]] = mesh.points[i];
    for (auto& t : shuffled.tetrahedra)
        for (int& v : t) v = perm[v];
    Scene a(mesh), b(shuffled);
    addMaterial(a.root, "CompressibleMooneyRivlin", "mat");
    addMaterial(b.root, "CompressibleMooneyRivlin", "mat");
    a.init();
    b.init();
    a.state->x() = deformed(mesh.points, 0.002);
    for (size_t i = 0; i < perm.size(); ++i) b.state->x()[perm[i]] = a.state->x()[i];
    const Positions fa = a.forces(), fb = b.forces();
    double err = 0;
    for (size_t i = 0; i < perm.size(); ++i) err = std::max(err, (fa[i] - fb[perm[i]]).norm());
    CHECK(err < 1e-12 * maxNorm(fa));
}

TEST_CASE("Prony viscoelasticity relaxes the forces by HEML eq. (18)-(20)", "[HEMLForceField]") {
    const MeshData mesh = cubeMesh(2, 2, 2);
    const double alpha = 0.4, tau = 0.05, dt = 0.01;
    const std::string apply = GENERATE("isochoric", "both");
    Scene s(mesh);
    addMaterial(s.root, "NeoHookean", "mat");
    auto& visco = s.root.add<viscoelastic::ViscoelasticProny>("visco");
    visco.findParam("alpha")->read("0.4", {});
    visco.findParam("tau")->read("0.05", {});
    visco.findParam("apply")->read(apply, {});
    s.init();
    visco.setTimeStep(dt);
    const double B = tau / (dt + tau);

    SECTION("a held shear relaxes towards alpha_inf times the elastic force") {
        // isochoric deformation (J = 1): both settings relax it fully
        for (size_t i = 0; i < mesh.points.size(); ++i) {
            const Vec3& X = mesh.points[i];
            s.state->x()[i] = X + Vec3(0.3 * X.y(), 0, 0);
        }
        Positions fe(s.state->size(), Vec3::Zero());
        {
            heml::HEMLForceField& ff = *s.ff;
            // elastic reference from a field without the Prony component
            core::Node n("elastic");
            auto& st = n.add<TestState>("mo");
            st.setRest(mesh.points);
            addMaterial(n, "NeoHookean", "mat");
            auto& e = n.add<heml::HEMLForceField>("ff");
            e.m_mesh.set(mesh);
            for (auto& c : n.components()) c->init();
            st.x() = s.state->x();
            e.addForce(st, fe, 0);
            (void)ff;
        }
        for (int step = 1; step <= 30; ++step) {
            const Positions f = s.forces(step * dt);
            // gamma^n = alpha f (1 - B^n) for a constant f  (eq. (20) from gamma^0 = 0)
            const double factor = 1.0 - alpha * (1.0 - std::pow(B, step));
            double err = 0;
            for (size_t i = 0; i < f.size(); ++i) err = std::max(err, (f[i] - factor * fe[i]).norm());
            CAPTURE(step);
            CHECK(err < 1e-12 * maxNorm(fe));
        }
        // calling addForce again at the same time does not advance the history
        const Positions again = s.forces(30 * dt);
        const Positions once = s.forces(30 * dt);
        CHECK(maxNorm(again) == maxNorm(once));
        CHECK(maxNorm(again) == Approx((1.0 - alpha * (1.0 - std::pow(B, 30))) * maxNorm(fe)).epsilon(1e-12));
    }
    SECTION("a held dilation relaxes only when the volumetric part does") {
        for (size_t i = 0; i < mesh.points.size(); ++i) s.state->x()[i] = 1.05 * mesh.points[i];
        const Positions f1 = s.forces(dt);
        for (int step = 2; step <= 40; ++step) s.forces(step * dt);
        const Positions fn = s.forces(40 * dt);
        const double ratio = maxNorm(fn) / maxNorm(f1);
        if (apply == "isochoric") CHECK(ratio == Approx(1.0).epsilon(1e-9));
        else CHECK(ratio == Approx((1 - alpha * (1 - std::pow(B, 40))) / (1 - alpha * (1 - B))).epsilon(1e-9));
    }
}

TEST_CASE("stable time step: shortest altitude over the dilatational wave speed", "[HEMLForceField]") {
    MeshData mesh;
    mesh.points = {Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0, 0.01, 0), Vec3(0, 0, 0.01)};
    mesh.tetrahedra = {{0, 1, 2, 3}};
    Scene s(mesh);
    addMaterial(s.root, "NeoHookean", "mat");  // mu 1000, kappa 20000
    s.mass->rho = 1000;
    s.init();
    // shortest altitude: onto the slanted face, 0.01 / sqrt(3)
    const double h = 0.01 / std::sqrt(3.0), c = std::sqrt((20000 + 4.0 / 3.0 * 1000) / 1000);
    CHECK(s.ff->stableTimeStep(*s.state) == Approx(h / c).epsilon(1e-12));

    SECTION("mass-spring mode bounds it by the spring frequencies") {
        Scene m(mesh);
        m.ff->m_stiffness.set(100);
        m.mass->setMasses({0.25, 0.25, 0.25, 0.25});
        m.init();
        // node 0: three springs, sum_j k (1/m_i + 1/m_j) = 3 * 100 * 8 = 2400
        CHECK(m.ff->stableTimeStep(*m.state) == Approx(2.0 / std::sqrt(2400.0)).epsilon(1e-12));
    }
}

TEST_CASE("cell data: J and the von Mises stress of a homogeneous stretch", "[HEMLForceField]") {
    const MeshData mesh = cubeMesh(2, 2, 2);
    Scene s(mesh);
    addMaterial(s.root, "NeoHookean", "mat");
    s.init();
    const Mat3 F = Vec3(1.0, 1.0, 1.2).asDiagonal();
    for (size_t i = 0; i < mesh.points.size(); ++i) s.state->x()[i] = F * mesh.points[i];
    std::vector<core::CellField> cells;
    s.ff->cellData(*s.state, cells);
    REQUIRE(cells.size() == 2);
    CHECK(cells[0].name == "J");
    CHECK(cells[1].name == "vonMises");
    // NeoHookean mu = 1000, kappa = 20000: sigma = mu/J J^(-2/3) dev(B) + kappa (J - 1) I; von Mises = mu J^(-5/3) |b_zz - b_xx|
    const double J = 1.2, vm = 1000 * std::pow(J, -5.0 / 3.0) * (1.44 - 1.0);
    for (size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
        CHECK(cells[0].values[e] == Approx(J).epsilon(1e-12));
        CHECK(cells[1].values[e] == Approx(vm).epsilon(1e-10));
    }
}

TEST_CASE("set-up errors are located and say what to do", "[HEMLForceField]") {
    const MeshData mesh = cubeMesh(1, 1, 1);
    SECTION("no material") {
        Scene s(mesh);
        CHECK_THROWS_WITH(s.init(), Catch::Contains("no material"));
    }
    SECTION("mesh and tetrahedra both") {
        Scene s(mesh);
        addMaterial(s.root, "NeoHookean", "mat");
        s.ff->m_tetrahedra.set(mesh.tetrahedra);
        CHECK_THROWS_WITH(s.init(), Catch::Contains("not both"));
    }
    SECTION("a group material that is not a material") {
        Scene s(mesh);
        addMaterial(s.root, "NeoHookean", "mat");
        s.ff->m_groupMaterials.set("1 @mo");
        CHECK_THROWS_WITH(s.init(), Catch::Contains("not a material"));
    }
    SECTION("an unknown group name") {
        Scene s(mesh);
        addMaterial(s.root, "NeoHookean", "mat");
        s.ff->m_groupMaterials.set("lefft @mat");
        CHECK_THROWS_WITH(s.init(), Catch::Contains("did you mean 'left'"));
    }
    SECTION("a group left without material") {
        Scene s(mesh);
        addMaterial(s.root, "NeoHookean", "mat");
        s.ff->m_groupMaterials.set("1 @mat");  // the single cube is in group 1... all of it
        MeshData m2 = mesh;
        m2.tetrahedronGroup.assign(m2.tetrahedra.size(), 3);
        s.ff->m_mesh.set(m2);
        CHECK_THROWS_WITH(s.init(), Catch::Contains("group 3"));
    }
    SECTION("a missing fibre array") {
        Scene s(mesh);
        addMaterial(s.root, "TransverselyIsotropic", "mat");
        s.ff->m_fibreArray.set("fibers");
        CHECK_THROWS_WITH(s.init(), Catch::Contains("no cell array 'fibers'"));
    }
    SECTION("a degenerate tetrahedron") {
        MeshData flat;
        flat.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
        flat.tetrahedra = {{0, 1, 2, 3}};
        Scene s(flat);
        addMaterial(s.root, "NeoHookean", "mat");
        CHECK_THROWS_WITH(s.init(), Catch::Contains("degenerate"));
    }
    SECTION("a second ViscoelasticProny (HEML relaxes one series; it took the first and ignored the rest)") {
        Scene s(mesh);
        addMaterial(s.root, "NeoHookean", "mat");
        for (const char* name : {"shear", "bulk"}) {
            auto& visco = s.root.add<viscoelastic::ViscoelasticProny>(name);
            visco.findParam("alpha")->read("0.4", {});
            visco.findParam("tau")->read("0.05", {});
        }
        CHECK_THROWS_WITH(s.init(), Catch::Contains("ViscoelasticProny 'bulk'") && Catch::Contains("a second ViscoelasticProny") &&
                                        Catch::Contains("one ViscoelasticProny"));
    }
    SECTION("a node index out of range") {
        MeshData bad = mesh;
        bad.tetrahedra[0][2] = 99;
        Scene s(bad);
        addMaterial(s.root, "NeoHookean", "mat");
        CHECK_THROWS_WITH(s.init(), Catch::Contains("node 99"));
    }
}
