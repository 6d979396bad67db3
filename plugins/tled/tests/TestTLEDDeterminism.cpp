// TLEDForceField gives bitwise the same forces, energy, stresses and trajectory with 1, 2 and 3
// threads and with both layouts of its block buffers (node ranges and compact rows, nodeBuffers)
// (docs/design.md, principle 5) on every force path: elastic tetrahedra, hexahedra with hourglass control,
// a material outside the built-in laws (batched evaluation), fibres per element (fibreArray,
// fibreArray2), and the viscous loops (one term, several terms in two series, and CompressibleNeoHookean
// with a two-term series of every apply value), and precision="mixed". Each mesh has
// 24 element blocks or more (2048 tetrahedra or 512 hexahedra each), so that 3 threads take them in
// a varying order: an order-dependent sum of the block buffers would show. The force field adds to
// a force vector that already holds other forces (as the mechanical group's m g and external
// forces): from zero, two blocks' contributions to a shared node sum to the same bits in either
// order (a + b = b + a), so an order-dependent scatter would go unseen.
#include "../../materials/tests/LawReference.h"
#include "TLEDTestSupport.h"

#include "fascia/materials/Conformance.h"

#include <catch2/catch.hpp>

#include <omp.h>

#include <cmath>
#include <cstring>
#include <random>

using namespace tledtest;

namespace {

// a material that is not a Material<Law>: the force field runs its generic loop for it
using Wrapped = materials::conformance::GenericMaterial;

struct Run {
    Positions f1, x;
    std::vector<Positions> f1again;  ///< the first forces evaluated again, kRepeats times
    double energy = 0;
    std::vector<double> S;           ///< the stresses at the end
    size_t blocks = 0;
    bool compact = false;            ///< the layout the force field used
};

bool bitwiseEqual(const Positions& a, const Positions& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

/// Forces already in the vector the force field adds to (as the group's m g and external forces).
Positions preload(size_t n) {
    Positions f(n);
    for (size_t i = 0; i < n; ++i) f[i] = 1e-3 * Vec3(std::sin(1.0 + i), std::cos(2.0 + i), -1.0 / (3.0 + i));
    return f;
}

/// The first forces are evaluated this many times more: each evaluation is a new draw of the order in
/// which the threads finish the blocks (cheap next to building the force field).
constexpr int kRepeats = 40;

/// Three steps of semi-implicit Euler (v += dt f / m, x += dt v) from a deformed state at rest.
Run runPath(const std::string& path, const fascia::MeshData& mesh, int threads, const std::string& layout) {
    omp_set_num_threads(threads);
    Bench b(mesh.points);
    // "compressible <apply>": CompressibleNeoHookean with a two-term series of each apply value (the
    // isochoric and volumetric ones move its s ln J between the parts, materials/RelaxationSplit.h)
    const bool compressible = path.rfind("compressible ", 0) == 0;
    const std::string type = compressible                          ? "CompressibleNeoHookean"
                             : path == "fibres one term"             ? "TransverselyIsotropic"
                             : path == "orthotropic two series"    ? "Orthotropic"
                             : path == "generic"                   ? "CompressibleMooneyRivlin"
                                                                   : "NeoHookean";
    auto& mat = b.material(type, lawref::lawNamed(type).params(), "mat");
    if (path == "fibres one term") b.prony("0.4", "0.001", "isochoric");
    if (compressible) b.prony("0.3 0.2", "0.002 0.0005", path.substr(13));
    if (path == "orthotropic two series") {
        b.prony("0.3 0.2", "0.002 0.0005", "isochoric", "visco");
        b.prony("0.1", "0.001", "volumetric", "visco2");
    }
    auto& ff = b.forceField({}, {});
    ff.m_mesh.set(mesh);
    if (path == "generic") {
        auto& w = b.root.add<Wrapped>("wrapped");
        w.inner = &mat;
        ff.m_material.set(&w);
    }
    if (path == "fibres one term") setParams(ff, {{"fibreArray", "fibres"}});
    if (path == "orthotropic two series") setParams(ff, {{"fibreArray", "fibres"}, {"fibreArray2", "fibres2"}});
    if (path == "mixed tetrahedra") setParams(ff, {{"precision", "mixed"}});
    setParams(ff, {{"nodeBuffers", layout}});
    ff.init();
    const double dt = 1e-4, m = 1000 * 1e-6;  // about rho h^3 per node
    ff.dtChanged(dt);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-1, 1);
    for (size_t i = 0; i < mesh.points.size(); ++i)
        b.state->x()[i] = 1.02 * mesh.points[i] + 4e-4 * Vec3(u(rng), u(rng), u(rng));
    Positions v(mesh.points.size(), Vec3::Zero());
    Run r;
    r.blocks = ff.blockCount();
    for (int n = 0; n < 3; ++n) {
        Positions f = preload(mesh.points.size());
        b.ff->addForce(*b.state, f, n * dt);
        if (n == 0) {
            r.f1 = f;
            for (int k = 0; k < kRepeats; ++k) {  // the same state and time: the viscous history stays
                Positions g = preload(mesh.points.size());
                b.ff->addForce(*b.state, g, 0);
                r.f1again.push_back(std::move(g));
            }
        }
        for (size_t i = 0; i < v.size(); ++i) {
            v[i] += dt / m * f[i];
            b.state->x()[i] += dt * v[i];
        }
    }
    r.x = b.state->x();
    r.energy = ff.potentialEnergy(*b.state);
    ff.stresses(*b.state, 2 * dt, r.S);
    r.compact = ff.compactBuffers();
    return r;
}

} // namespace

TEST_CASE("TLEDForceField forces, energy, stresses and a short trajectory are bitwise identical with 1, 2 and 3 threads "
          "and both buffer layouts on 24 blocks",
          "[TLEDForceField][determinism]") {
    const std::string path = GENERATE("elastic tetrahedra", "hexahedra", "generic", "fibres one term", "orthotropic two series",
                                        "compressible isochoric", "compressible volumetric", "compressible both", "mixed tetrahedra");
    const bool hexes = path == "hexahedra" || path == "orthotropic two series";
    fascia::MeshData mesh;
    if (hexes) {
        // 16 x 16 x 48 cubes: 12288 hexahedra, 24 blocks of 512
        mesh.points = gridPoints(16, 16, 48, 0.01);
        mesh.hexahedra = gridHexes(16, 16, 48);
    } else {
        // 16 x 16 x 32 cubes of 6 tetrahedra: 49152 elements, 24 blocks of 2048
        mesh.points = gridPoints(16, 16, 32, 0.01);
        mesh.tetrahedra = gridTets(16, 16, 32);
    }
    const size_t ne = hexes ? mesh.hexahedra.size() : mesh.tetrahedra.size();
    std::vector<double> a, bb;
    lawref::elementFibres(ne, a, bb);
    mesh.cellArrays["fibres"] = a;
    mesh.cellArrays["fibres2"] = bb;
    const int saved = omp_get_max_threads();
    const Run one = runPath(path, mesh, 1, "range");
    CAPTURE(path, one.blocks);
    REQUIRE(one.blocks >= 24);
    REQUIRE(!one.compact);
    double scale = 0;
    for (const Vec3& v : one.f1) scale = std::max(scale, v.norm());
    REQUIRE(scale > 0);
    // each multi-threaded run three times, in both layouts: the order in which threads take the
    // blocks varies from run to run, and a single run can happen to repeat the serial order
    const std::pair<int, const char*> runs[] = {{1, "compact"}, {2, "range"},   {3, "compact"}, {2, "compact"},
                                                {3, "range"},   {2, "compact"}, {3, "range"}};
    for (const auto& [threads, layout] : runs) {
        const Run other = runPath(path, mesh, threads, layout);
        CAPTURE(threads, layout);
        CHECK(other.compact == (std::string(layout) == "compact"));
        CHECK(bitwiseEqual(one.f1, other.f1));
        int differ = 0;
        for (const auto& g : other.f1again) differ += !bitwiseEqual(one.f1, g);
        CHECK(differ == 0);
        CHECK(bitwiseEqual(one.x, other.x));
        CHECK(std::memcmp(&one.energy, &other.energy, sizeof(double)) == 0);
        CHECK((other.S.size() == one.S.size() && std::memcmp(one.S.data(), other.S.data(), one.S.size() * sizeof(double)) == 0));
    }
    omp_set_num_threads(saved);
}
