#pragma once
// Helpers for the cuda plugin's tests (the CPU emulation and the device tests): scenes of a small
// cantilever (a 2 x 2 x 3 cell box of tetrahedra, hexahedra or both, fixed at z = 0, pulled at
// z = 0.03, under gravity)
// with each law of the device step, the forces of TLEDForceField at a deformed state, and the
// arrays the device step builds for them.
#include "DeviceLaws.h"
#include "StepRunner.h"

#include "fascia/base/Error.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <memory>
#include <random>
#include <utility>
#include <string>
#include <type_traits>
#include <vector>

namespace cudatest {

namespace core = fascia::core;
namespace cuda = fascia::cuda;
using fascia::Positions;
using fascia::Vec3;

/// A law of the device step with moderate parameters (soft tissue, kPa), as its XML element.
struct Law {
    std::string name, element;
};

/// Every law of the device step (cuda::DeviceMaterials) with its example parameters (kExample:
/// fibre directions included), in list order.
inline std::vector<Law> deviceLaws() {
    std::vector<Law> out;
    fascia::materials::detail::forEachIn(
        [&](auto* tag) {
            const std::string name = std::decay_t<decltype(*tag)>::kName;
            std::string element = "<" + name + " name=\"mat\"";
            for (const auto& [key, value] : fascia::materials::exampleParameters(name)) element += " " + key + "=\"" + value + "\"";
            out.push_back({name, element + "/>"});
        },
        cuda::DeviceMaterials{});
    return out;
}

/// The law of that name from deviceLaws().
inline Law deviceLaw(const std::string& name) {
    for (const Law& l : deviceLaws())
        if (l.name == name) return l;
    FAIL("no device law " << name);
    return {};
}

/// The cantilever's elements: the grid's 6 tetrahedra per cell, its hexahedra, or hexahedra in the
/// bottom layer of cells (z < 0.01) and tetrahedra above (the same 36 nodes in every case).
enum class Mesh { Tets, Hexes, Mixed };

inline std::string meshName(Mesh m) { return m == Mesh::Tets ? "tetrahedra" : m == Mesh::Hexes ? "hexahedra" : "mixed"; }

/// The cantilever's elements in the grid's node numbering (node i + 3 (j + 3 k) at 0.01 (i, j, k)):
/// per cell (i, j, k), by k, then j, then i, either 6 tetrahedra (each positively oriented) or one
/// hexahedron (VTK order); hexahedra in every cell, in the bottom layer (k = 0) only, or nowhere.
/// cell(i, j, k) is called with the grid cell of each element as it is added.
template <class Cell>
void cantileverElements(bool hexAll, bool hexBottom, std::vector<std::array<int, 4>>& tets, std::vector<std::array<int, 8>>& hexes,
                        Cell&& cell) {
    const auto id = [](int i, int j, int k) { return i + 3 * (j + 3 * k); };
    static const int T[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
    static const int xi[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                const int c[8] = {id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
                                  id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
                if (hexAll || (hexBottom && k == 0)) {
                    hexes.push_back({c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]});
                    cell(i, j, k);
                    continue;
                }
                for (const auto& t : T) {
                    int q[4] = {t[0], t[1], t[2], t[3]};
                    // orientation from the unit cell's corners: det(p1 - p0, p2 - p0, p3 - p0) > 0
                    const auto d = [&](int r, int x) { return xi[q[r]][x] - xi[q[0]][x]; };
                    const int det = d(1, 0) * (d(2, 1) * d(3, 2) - d(2, 2) * d(3, 1)) - d(1, 1) * (d(2, 0) * d(3, 2) - d(2, 2) * d(3, 0)) +
                                    d(1, 2) * (d(2, 0) * d(3, 1) - d(2, 1) * d(3, 0));
                    if (det < 0) std::swap(q[1], q[2]);
                    tets.push_back({c[q[0]], c[q[1]], c[q[2]], c[q[3]]});
                    cell(i, j, k);
                }
            }
}

/// The TLEDForceField attributes of the mixed mesh: its elements given explicitly (hexahedra in the
/// bottom layer of cells, tetrahedra above).
inline std::string mixedElements() {
    std::vector<std::array<int, 4>> t4;
    std::vector<std::array<int, 8>> h8;
    cantileverElements(false, true, t4, h8, [](int, int, int) {});
    std::string tets, hexes;
    for (const auto& t : t4)
        for (int a : t) tets += std::to_string(a) + " ";
    for (const auto& h : h8)
        for (int a : h) hexes += std::to_string(a) + " ";
    return " tetrahedra=\"" + tets + "\" hexahedra=\"" + hexes + "\"";
}

/// The parts of the cantilever scene that differ between cases: the mesh source, the material
/// elements, the element force field's attributes beyond its name and J0, and its class.
struct BodyParts {
    std::string mesh, materials, ff;
    std::string forceField = "TLEDForceField";
};

/// The cantilever scene of these parts; `root` goes into the root node (a CudaStep), `body` into the
/// body's node.
inline std::string scene(const BodyParts& parts, const std::string& root, const std::string& body = "",
                         const std::string& integrator = "<SemiImplicitEuler damping=\"5\"/>") {
    return "<Node name=\"root\" dt=\"2e-5\" gravity=\"0 -9.81 0\" gravityCurve=\"linear 0 1 0.004 0.5\">\n" + root +
           "\n  <Node name=\"body\">\n    " + parts.mesh +
           "\n"
           "    <MechanicalObject name=\"mo\"/>\n"
           "    <LumpedMass density=\"1000\"/>\n    " +
           integrator + "\n    " + parts.materials + "\n    <" + parts.forceField + " name=\"ff\" J0=\"0.3\"" + parts.ff +
           "/>\n"
           "    <FixedConstraint name=\"clamp\" indices=\"0 1 2 3 4 5 6 7 8\"/>\n"
           "    <FixedConstraint name=\"roller\" indices=\"12 13\" directions=\"1 0 0\"/>\n"
           "    <ConstantForce name=\"pull\" indices=\"27 28 29 30 31 32 33 34 35\" force=\"0.002 0.001 0.004\"/>\n" +
           body + "\n  </Node>\n</Node>\n";
}

/// The cantilever scene (a 2 x 2 x 3 cell grid, fixed at z = 0, pulled at z = 0.03, under gravity)
/// with one material, the law's.
inline std::string scene(const Law& law, const std::string& root, const std::string& body = "",
                         const std::string& integrator = "<SemiImplicitEuler damping=\"5\"/>", Mesh mesh = Mesh::Tets) {
    const std::string grid = "<GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"" +
                             std::string(mesh == Mesh::Tets ? "tetrahedra6" : "hexahedra") + "\"/>";
    return scene(BodyParts{grid, law.element, mesh == Mesh::Mixed ? mixedElements() : std::string()}, root, body, integrator);
}

/// The CudaStep of a scene's root node in that precision ("double" or "float"): through the CPU
/// emulation of its kernels, or on the GPU.
inline std::string emulated(const std::string& precision) { return "<CudaStep emulate=\"true\" precision=\"" + precision + "\"/>"; }
inline std::string onGpu(const std::string& precision) { return "<CudaStep precision=\"" + precision + "\"/>"; }
/// The largest relative difference from the CPU allowed to a CudaStep of that precision: 1e-4 in
/// float, inDouble (1e-11 for trajectories) in double.
inline double deviceTolerance(const std::string& precision, double inDouble = 1e-11) { return precision == "double" ? inDouble : 1e-4; }

/// Deforms the state: x = A X + a jitter (seeded), v = 0.
inline void deform(core::BaseMechanicalState& mo, double scale) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> r(-1, 1);
    fascia::Mat3 A;
    A << 1 + 0.1 * scale, 0.05 * scale, -0.02 * scale, 0.03 * scale, 1 - 0.08 * scale, 0.04 * scale, -0.06 * scale, 0.02 * scale,
        1 + 0.12 * scale;
    for (size_t i = 0; i < mo.size(); ++i) mo.x()[i] = A * mo.x0()[i] + 4e-4 * scale * Vec3(r(rng), r(rng), r(rng));
}

/// u = x - X and v of a state, 3 per node.
inline void stateArrays(const core::BaseMechanicalState& mo, std::vector<double>& u, std::vector<double>& v) {
    u.resize(3 * mo.size());
    v.resize(3 * mo.size());
    for (size_t i = 0; i < mo.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            u[3 * i + size_t(c)] = mo.x()[i][c] - mo.x0()[i][c];
            v[3 * i + size_t(c)] = mo.v()[i][c];
        }
}

/// A number in scientific notation, for CAPTURE (Catch prints small doubles as 0.0).
inline std::string sci(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", x);
    return b;
}

/// max_i |a_i - b_i| / max_i |b_i| over 3-vectors (b as Positions, a flat).
inline double relativeError(const std::vector<double>& a, const Positions& b) {
    double num = 0, den = 0;
    for (size_t i = 0; i < b.size(); ++i) {
        const Vec3 d(a[3 * i] - b[i][0], a[3 * i + 1] - b[i][1], a[3 * i + 2] - b[i][2]);
        num = std::max(num, d.norm());
        den = std::max(den, b[i].norm());
    }
    return num / den;
}

/// The forces of TLEDForceField 'ff' at a deformed state, and the device step's setup of the scene.
struct ForceProbe {
    std::unique_ptr<core::Simulation> sim;
    Positions f;               ///< TLED's internal forces
    std::vector<double> u, v;  ///< the deformed state as the device step takes it
    cuda::StepSetup setup;
};

/// The same for a scene's XML.
inline ForceProbe probeForces(const std::string& xml, double scale) {
    ForceProbe p;
    p.sim = core::Simulation::fromString(xml);
    p.sim->init();
    auto& mo = p.sim->state("mo");
    deform(mo, scale);
    auto* ff = dynamic_cast<core::BaseForceField*>(p.sim->find("ff"));
    REQUIRE(ff);
    p.f.assign(mo.size(), Vec3::Zero());
    ff->addForce(mo, p.f, 0);
    stateArrays(mo, p.u, p.v);
    p.setup = cuda::buildStepSetup(*ff, p.sim->groups().at(0));
    return p;
}

/// The internal forces of one element pass of the runner make(p.setup, precision) at the probe's
/// state, relative to the force field's (relativeError).
template <class MakeRunner>
double forceError(MakeRunner&& make, const ForceProbe& p, cuda::Precision precision) {
    auto runner = make(p.setup, precision);
    runner->setState(p.u, p.v);
    runner->elementPass();
    std::vector<double> f;
    runner->internalForces(f);
    REQUIRE(f.size() == 3 * p.f.size());
    return relativeError(f, p.f);
}

/// forceError in double and in float, against the bounds of every force comparison of the device
/// step: 1e-12 relative in double, 1e-5 in float.
template <class MakeRunner>
void checkForces(MakeRunner&& make, const ForceProbe& p) {
    for (const cuda::Precision precision : {cuda::Precision::Double, cuda::Precision::Float}) {
        const bool useFloat = precision == cuda::Precision::Float;
        const double err = forceError(make, p, precision);
        CAPTURE(useFloat, sci(err));
        CHECK(err <= (useFloat ? 1e-5 : 1e-12));
    }
}

inline ForceProbe probeForces(const Law& law, double scale, Mesh mesh = Mesh::Tets) {
    return probeForces(scene(law, "", "", "<SemiImplicitEuler damping=\"5\"/>", mesh), scale);
}

/// Positions after `steps` steps of the scene with `root` in its root node.
inline Positions trajectoryEnd(const Law& law, const std::string& root, int steps, Mesh mesh = Mesh::Tets) {
    auto sim = core::Simulation::fromString(scene(law, root, "", "<SemiImplicitEuler damping=\"5\"/>", mesh));
    sim->init();
    for (int s = 0; s < steps; ++s) sim->step();
    return sim->state("mo").x();
}

/// max_i |x_i - y_i| / max_i |y_i - X_i|: a trajectory's end against a reference, relative to the
/// reference's displacement.
inline double displacementError(const Positions& x, const Positions& y, const Positions& X) {
    double num = 0, den = 0;
    for (size_t i = 0; i < y.size(); ++i) {
        num = std::max(num, (x[i] - y[i]).norm());
        den = std::max(den, (y[i] - X[i]).norm());
    }
    return num / den;
}

/// A prescribed lift of nodes 12 (a roller in x: held there, lifted in y and z) and 30, 31 (pulled),
/// on y and z (a body element of scene()).
inline const std::string kLift =
    "<PrescribedDisplacement name=\"lift\" indices=\"12 30 31\" directions=\"0 1 1\" displacement=\"0 0.001 0.002\" "
    "shape=\"smooth\" rampTime=\"0.01\"/>";

/// The Input error of initialising sim, built and changed in code before init (empty when it
/// initialises).
inline std::string initError(core::Simulation& sim) {
    try {
        sim.init();
    } catch (const core::Error& e) {
        CHECK(e.kind() == core::ErrorKind::Input);
        return e.what();
    }
    return {};
}

/// The Input error of initialising a scene (empty when it initialises).
inline std::string initError(const std::string& xml) {
    try {
        auto sim = core::Simulation::fromString(xml);
        sim->init();
    } catch (const core::Error& e) {
        CHECK(e.kind() == core::ErrorKind::Input);
        return e.what();
    }
    return {};
}

/// A Prony series of two terms that relax noticeably within a run of 1000 steps of 2e-5 s (a body
/// element of scene()), relaxing the given part ("isochoric", "volumetric" or "both").
inline std::string prony(const std::string& apply = "isochoric") {
    return "<ViscoelasticProny name=\"visco\" alpha=\"0.5 0.2\" tau=\"0.01 0.002\" apply=\"" + apply + "\"/>";
}

/// Two series, one per part, of two and one terms (the states of both in one array).
inline const std::string kTwoSeries =
    "<ViscoelasticProny name=\"shear\" alpha=\"0.4 0.2\" tau=\"0.01 0.002\" apply=\"isochoric\"/>"
    "<ViscoelasticProny name=\"bulk\" alpha=\"0.3\" tau=\"0.004\" apply=\"volumetric\"/>";

/// The ends of a trajectory of the scene on the CPU and with `root` (a CudaStep), and their
/// difference relative to the CPU's largest displacement.
struct Pair {
    Positions cpu, device, rest;
    double err = 0, moved = 0;
};

/// The same for the scene of `parts`.
inline Pair runBoth(const BodyParts& parts, const std::string& body, const std::string& integrator, const std::string& root, int steps) {
    Pair r;
    for (int k = 0; k < 2; ++k) {
        auto sim = core::Simulation::fromString(scene(parts, k == 0 ? "" : root, body, integrator));
        for (int s = 0; s < steps; ++s) sim->step();
        (k == 0 ? r.cpu : r.device) = sim->state("mo").x();
        r.rest = sim->state("mo").x0();
    }
    r.err = displacementError(r.device, r.cpu, r.rest);
    for (size_t i = 0; i < r.cpu.size(); ++i) r.moved = std::max(r.moved, (r.cpu[i] - r.rest[i]).norm());
    return r;
}

inline Pair runBoth(const Law& law, const std::string& body, const std::string& integrator, Mesh mesh, const std::string& root, int steps) {
    const std::string grid = "<GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"" +
                             std::string(mesh == Mesh::Tets ? "tetrahedra6" : "hexahedra") + "\"/>";
    return runBoth(BodyParts{grid, law.element, mesh == Mesh::Mixed ? mixedElements() : std::string()}, body, integrator, root, steps);
}

} // namespace cudatest
