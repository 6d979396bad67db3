/// fascia-bench's yardsticks: the reference kernel's forces agree with TLEDForceField's (the same
/// neo-Hookean law on the same mesh and state, to 1e-12 of the largest force), its step is
/// semi-implicit Euler; and the bytes the force fields report match a hand count on one cube cell.
#include "Bench.h"
#include "ReferenceKernel.h"

#include "fascia/sim/LayoutBytes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace fascia;
using namespace fascia::bench;

namespace {

Case tledCube(int cube, const std::string& ff = "TLED") {
    Case c;
    c.cube = cube;
    c = sideBySide(c, ff);  // TLED: NeoHookean, the reference kernel's law
    return c;
}

ReferenceTLED referenceOf(core::Simulation& sim, int threads) {
    auto* ff = dynamic_cast<core::BaseForceField*>(sim.find("ff"));
    REQUIRE(ff);
    const core::MechanicalGroup& g = sim.groups().at(0);
    const double mu = kYoung / (2 * (1 + kPoisson)), kappa = kYoung / (3 * (1 - 2 * kPoisson));
    ReferenceTLED ref(*ff->tetrahedra(), g.state->x0(), mu, kappa, g.mass, {}, threads);
    ref.setState(g.state->x());
    return ref;
}

core::LayoutBytes bytesOf(core::Simulation& sim) {
    auto* r = dynamic_cast<const core::LayoutReport*>(sim.find("ff"));
    REQUIRE(r);
    return r->layoutBytes();
}

} // namespace

TEST_CASE("ReferenceTLED: its forces are TLEDForceField's (neo-Hookean, same mesh) to 1e-12", "[bench]") {
    for (int threads : {1, 2}) {
        auto sim = build(tledCube(6), threads);  // 1,296 tetrahedra, deformed by two waves
        auto* ff = dynamic_cast<core::BaseForceField*>(sim->find("ff"));
        auto& st = sim->state("state");
        Positions f(st.size(), Vec3::Zero());
        ff->addForce(st, f, sim->time());
        ReferenceTLED ref = referenceOf(*sim, threads);
        CHECK(ref.elementCount() == ff->elementCount());
        std::vector<double> fr;
        ref.forces(fr);
        double fmax = 0, err = 0;
        for (size_t i = 0; i < st.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                fmax = std::max(fmax, std::abs(f[i][c]));
                err = std::max(err, std::abs(fr[3 * i + size_t(c)] - f[i][c]));
            }
        REQUIRE(fmax > 0);
        CHECK(err <= 1e-12 * fmax);
    }
}

TEST_CASE("ReferenceTLED: a step is v += dt f / m, x += dt v, fixed nodes held", "[bench]") {
    auto sim = build(tledCube(3), 2);
    const core::MechanicalGroup& g = sim->groups().at(0);
    const double mu = kYoung / (2 * (1 + kPoisson)), kappa = kYoung / (3 * (1 - 2 * kPoisson));
    const IndexList fixed = {0, 1};
    ReferenceTLED ref(*dynamic_cast<core::BaseForceField*>(sim->find("ff"))->tetrahedra(), g.state->x0(), mu, kappa, g.mass,
                      fixed, 2);
    ref.setState(g.state->x());
    std::vector<double> f;
    ref.forces(f);
    const std::vector<double> x0 = ref.x();
    const double dt = 1e-4;
    ref.step(dt);
    for (size_t i = 0; i < ref.nodeCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            const size_t k = 3 * i + size_t(c);
            const bool held = i < 2;
            const double expect = held ? g.state->x0()[i][c] : x0[k] + dt * dt * f[k] / g.mass[i];
            CHECK(ref.x()[k] == Approx(expect).epsilon(1e-14).margin(1e-15));
        }
}

TEST_CASE("layoutBytes: TLED and HEML on one cube cell match a hand count", "[bench]") {
    // one cell: 8 nodes, 6 tetrahedra, one block, the state's node order
    auto tled = build(tledCube(1, "TLED"), 1);
    const core::LayoutBytes t = bytesOf(*tled);
    // element data: one batch of 32 slots of 9 rows (dN_1..3/dX) in doubles, 6 volumes, 6 x 4 node indices
    CHECK(t.elementData == 32 * 9 * 8 + 6 * 8 + 6 * 4 * 4);
    // buffers: 8 rows of 4 doubles, written by the block's commit (the scatter adds into the
    // thread's own rows, in its cache), read by the sum
    CHECK(t.buffers == 2 * 8 * 32);
    // nodes: x and X read (3 doubles), u written and read (4 doubles), f read and written
    CHECK(t.nodeRows == 2 * 8 * 24 + 2 * 8 * 32 + 2 * 8 * 24);

    auto heml = build(tledCube(1, "HEML"), 1);
    const core::LayoutBytes h = bytesOf(*heml);
    // element data: 16 slots (6 elements padded to the 16 lanes) of 4 node rows (int), Vol, 1 / det V, G (6)
    CHECK(h.elementData == 16 * (4 * 4 + 8 + 8 + 6 * 8));
    // nodes (8, read directly from the state): x read; the sum's row starts (9), nodeOf, f read and written
    CHECK(h.nodeRows == 8 * 24 + 9 * 4 + 8 * 4 + 2 * 8 * 24);
    // rows (8): row -> node list, forces written by the block's commit and read by the sum, the
    // sum's row list (the positions and forces of a block's run stay in its thread's cache)
    CHECK(h.buffers == 8 * 4 + 2 * 8 * 32 + 8 * 4);

    // with a one-term Prony series: its states, 6 per element slot, read and written
    Case v = tledCube(1, "TLED");
    v.viscous = true;
    auto tv = build(v, 1);
    CHECK(bytesOf(*tv).elementData == t.elementData + 2 * 32 * 6 * 8);
}
