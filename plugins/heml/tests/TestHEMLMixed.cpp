// HEMLForceField precision="mixed" (docs/design.md, section 3: element data and element math in float, node state,
// force sums and the energy sum in double): forces and energy agree with precision="double" on a
// deformed mesh (a smooth random displacement of a few per cent strain, and one of about 30 %) for
// an isotropic law, fibre laws, a user material through the double-only evaluate() and mass-spring
// mode; the element data is 48 instead of 80 bytes per element; an unknown precision is a located
// error; mixed forces are bitwise the same for 1 and 2 threads.
#include "../../materials/tests/LawReference.h"
#include "HEMLTestSupport.h"
#include "fascia/materials/Conformance.h"
#include "fascia/sim/Simulation.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include <catch2/catch.hpp>

#include <omp.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <random>

using namespace fascia;
using namespace hemltest;
using Catch::Matchers::Contains;

namespace {

const double kPi = 3.14159265358979323846;

/// A smooth random displacement of the mesh: u(X) = sum of 3 sine modes per component, scaled so
/// that the largest displacement gradient entry is about `strain`, plus a rigid offset (positions
/// away from the origin, as in a scene).
Positions smoothlyDeformed(const Positions& X, double strain, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    Vec3 lo = X[0], hi = X[0];
    for (const auto& p : X) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double L = (hi - lo).maxCoeff();
    struct Mode {
        Vec3 k, a;
        double phase;
    };
    std::vector<Mode> modes;
    for (int m = 0; m < 3; ++m) modes.push_back({Vec3(u(rng), u(rng), u(rng)) * (2 * kPi / L), Vec3(u(rng), u(rng), u(rng)), kPi * u(rng)});
    // the gradient of a sin(k.X + phase) is a k^T cos(...): at most |a|_inf |k|_inf per mode
    double g = 0;
    for (const auto& m : modes) g += m.a.cwiseAbs().maxCoeff() * m.k.cwiseAbs().maxCoeff();
    const double s = strain / g;
    Positions x(X.size());
    for (size_t i = 0; i < X.size(); ++i) {
        Vec3 d = Vec3::Zero();
        for (const auto& m : modes) d += m.a * std::sin(m.k.dot(X[i]) + m.phase);
        x[i] = X[i] + s * d + Vec3(0.3, -0.2, 0.5);
    }
    return x;
}

/// The largest |F - I| entry over the elements (the strain the test ran at).
double largestStrain(const MeshData& mesh, const Positions& x) {
    double m = 0;
    for (const auto& t : mesh.tetrahedra) {
        Mat3 V, v;
        for (int k = 0; k < 3; ++k) {
            V.col(k) = mesh.points[t[k + 1]] - mesh.points[t[0]];
            v.col(k) = x[t[k + 1]] - x[t[0]];
        }
        m = std::max(m, (v * V.inverse() - Mat3::Identity()).cwiseAbs().maxCoeff());
    }
    return m;
}

/// A scene on mesh for one force path, in the given precision. Paths: a built-in material name,
/// "generic" (CompressibleMooneyRivlin behind the double-only BaseMaterial::evaluate), "fibre arrays"
/// (Orthotropic with a0, b0 per element), "viscous" (NeoHookean with a Prony series), "springs".
std::unique_ptr<Scene> makeScene(const MeshData& mesh, const std::string& path, const std::string& precision) {
    auto s = std::make_unique<Scene>(mesh);
    s->ff->m_precision.set(precision);
    if (path == "springs") {
        s->ff->m_stiffness.set(20.0);
    } else {
        const std::string type = path == "generic"        ? "CompressibleMooneyRivlin"
                                 : path == "fibre arrays" ? "Orthotropic"
                                 : path == "viscous"      ? "NeoHookean"
                                                          : path;
        auto& mat = addMaterial(s->root, type, "mat");
        if (path == "generic") {
            mat.init();
            auto& w = s->root.add<materials::conformance::GenericMaterial>("wrapped");
            w.inner = &mat;
            s->ff->m_material.set(&w);
        }
        if (path == "fibre arrays") {
            s->ff->m_fibreArray.set("fibres");
            s->ff->m_fibreArray2.set("fibres2");
        }
        if (path == "viscous") {
            auto& visco = s->root.add<viscoelastic::ViscoelasticProny>("visco");
            visco.findParam("alpha")->read("0.3 0.2", {});
            visco.findParam("tau")->read("0.002 0.0005", {});
            visco.findParam("apply")->read("isochoric", {});
        }
    }
    s->init();
    if (auto* v = s->root.findLocal<viscoelastic::ViscoelasticProny>()) v->setTimeStep(1e-4);
    return s;
}

MeshData testMesh(int n) {
    MeshData mesh = cubeMesh(n, n, n, 0.01, 0.15, 11);
    std::vector<double> a, b;
    lawref::elementFibres(mesh.tetrahedra.size(), a, b);
    mesh.cellArrays["fibres"] = a;
    mesh.cellArrays["fibres2"] = b;
    return mesh;
}

double maxDifference(const Positions& a, const Positions& b) {
    double m = 0;
    for (size_t i = 0; i < a.size(); ++i) m = std::max(m, (a[i] - b[i]).norm());
    return m;
}

bool bitwiseEqual(const Positions& a, const Positions& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

} // namespace

TEST_CASE("HEML mixed precision forces and energy agree with double precision on a deformed mesh", "[HEMLForceField]") {
    const std::string path = GENERATE("NeoHookean", "TransverselyIsotropic", "fibre arrays", "generic", "viscous", "springs");
    const double strain = GENERATE(0.045, 0.45);  // about 3 % and 30 % largest |F - I| entry
    const MeshData mesh = testMesh(6);
    auto dbl = makeScene(mesh, path, "double");
    auto mix = makeScene(mesh, path, "mixed");
    const Positions x = smoothlyDeformed(mesh.points, strain, 5);
    const double measured = largestStrain(mesh, x);
    CAPTURE(path, strain, measured);
    REQUIRE(measured > 0.5 * strain);
    REQUIRE(measured < 2.0 * strain);
    // three steps at growing deformation (the viscous path's history builds up over them)
    double worstForce = 0;
    for (int n = 1; n <= 3; ++n) {
        const double t = n * 1e-4, grow = 0.8 + 0.1 * n;
        for (size_t i = 0; i < x.size(); ++i) {
            const Vec3 p = mesh.points[i] + grow * (x[i] - mesh.points[i]);
            dbl->state->x()[i] = p;
            mix->state->x()[i] = p;
        }
        const Positions fd = dbl->forces(t), fm = mix->forces(t);
        const double scale = maxNorm(fd);
        REQUIRE(scale > 0);
        worstForce = std::max(worstForce, maxDifference(fd, fm) / scale);
    }
    const double Ed = dbl->ff->potentialEnergy(*dbl->state), Em = mix->ff->potentialEnergy(*mix->state);
    REQUIRE(Ed > 0);
    const double energyError = std::abs(Em - Ed) / Ed;
    std::cout << "mixed vs double: " << path << ", strain " << measured << ": max force error " << worstForce
              << " of the largest force, energy error " << energyError << "\n";
    CHECK(worstForce < 1e-5);
    CHECK(energyError < 1e-5);
    // and not the same loop: the mixed forces differ from the double ones (float rounding)
    CHECK(worstForce > 0);
}

TEST_CASE("HEML mixed precision halves the element data: 48 instead of 80 bytes per element", "[HEMLForceField]") {
    const MeshData mesh = testMesh(4);
    auto dbl = makeScene(mesh, "NeoHookean", "double");
    auto mix = makeScene(mesh, "NeoHookean", "mixed");
    const double slots = double(dbl->ff->elementCount());  // 384 elements: 24 chunks of 16, no padding
    REQUIRE(std::fmod(slots, 16.0) == 0.0);
    CHECK(double(dbl->ff->layoutBytes().elementData) / slots == 80.0);
    CHECK(double(mix->ff->layoutBytes().elementData) / slots == 48.0);
}

TEST_CASE("HEML precision other than double or mixed is a located error", "[HEMLForceField]") {
    SECTION("set from code: at the simulation's init (the check of every component's values set from code)") {
        const MeshData mesh = cubeMesh(1, 1, 1);
        auto root = std::make_unique<core::Node>("root");
        root->add<TestState>("mo").setRest(mesh.points);
        root->add<TestMass>("mass");
        addMaterial(*root, "NeoHookean", "mat");
        auto& ff = root->add<heml::HEMLForceField>("ff");
        ff.m_mesh.set(mesh);
        ff.m_precision.set("single");
        core::Simulation sim(std::move(root));
        CHECK_THROWS_WITH(sim.init(), Contains("HEMLForceField 'ff'") && Contains("precision = single") &&
                                          Contains("one of double|mixed"));
    }
    SECTION("given in XML: at the attribute's line") {
        const std::string xml = "<Node name=\"root\" dt=\"1e-4\">\n"
                                "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.02\" resolution=\"2 2 2\" element=\"tetrahedra6\"/>\n"
                                "  <MechanicalObject name=\"mo\"/>\n"
                                "  <LumpedMass density=\"1000\"/>\n"
                                "  <NeoHookean name=\"mat\" mu=\"1000\" kappa=\"20000\"/>\n"
                                "  <HEMLForceField name=\"ff\" precision=\"float\"/>\n"
                                "</Node>\n";
        CHECK_THROWS_WITH(core::Simulation::fromString(xml, "precision.xml"),
                          Contains("precision.xml:6") && Contains("precision") && Contains("one of double|mixed"));
    }
}

TEST_CASE("HEML mixed precision forces are bitwise identical with 1 and 2 threads", "[HEMLForceField]") {
    const std::string path = GENERATE("NeoHookean", "fibre arrays", "generic", "viscous", "springs");
    // 8^3 cubes of 6 tetrahedra: 3072 elements, 3 blocks
    const MeshData mesh = testMesh(8);
    const Positions x = smoothlyDeformed(mesh.points, 0.05, 8);
    const int saved = omp_get_max_threads();
    const auto run = [&](int threads) {
        omp_set_num_threads(threads);
        auto s = makeScene(mesh, path, "mixed");
        REQUIRE(s->ff->blockCount() >= 3);
        s->state->x() = x;
        Positions f = s->forces(1e-4);
        const Positions f2 = s->forces(2e-4);  // the viscous path: a second step on the history
        f.insert(f.end(), f2.begin(), f2.end());
        const double E = s->ff->potentialEnergy(*s->state);
        return std::make_pair(f, E);
    };
    const auto one = run(1);
    CAPTURE(path);
    REQUIRE(maxNorm(one.first) > 0);
    for (int rep = 0; rep < 3; ++rep) {
        const auto two = run(2);
        CHECK(bitwiseEqual(one.first, two.first));
        CHECK(std::memcmp(&one.second, &two.second, sizeof(double)) == 0);
    }
    omp_set_num_threads(saved);
}
