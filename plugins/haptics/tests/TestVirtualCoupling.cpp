// The virtual coupling (fascia/haptics/VirtualCoupling.h): its force law, its proxy, and samples
// shared between two threads without tearing.
#include "fascia/haptics/VirtualCoupling.h"
#include "fascia/base/StateIO.h"

#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

using fascia::Vec3;
using fascia::haptics::CouplingSample;
using fascia::haptics::VirtualCoupling;

TEST_CASE("The coupling force is minus stiffness times the stretch minus damping times the relative velocity", "[VirtualCoupling]") {
    const VirtualCoupling c(300, 2.5);
    const Vec3 xd(0.1, 0.2, -0.05), vd(0.01, 0, 0.3), xt(0.1, 0.19, -0.045), vt(0, 0.02, 0.1);
    const Vec3 f = c.force(xd, vd, xt, vt);
    CHECK(f.isApprox(Vec3(-300 * 0.0 - 2.5 * 0.01, -300 * 0.01 - 2.5 * -0.02, -300 * -0.005 - 2.5 * 0.2), 1e-14));
    // the proxy: the spring balances the contact force there, so the force felt is the contact force
    const Vec3 contact(0.5, -1.0, 2.0);
    const Vec3 target = c.toolTarget(xd, contact);
    CHECK(c.force(xd, Vec3::Zero(), target, Vec3::Zero()).isApprox(contact, 1e-14));
    CHECK(c.toolTarget(xd, Vec3::Zero()) == xd);
}

TEST_CASE("A coupling without stiffness or with negative damping is refused", "[VirtualCoupling]") {
    CHECK_THROWS_AS(VirtualCoupling(0, 1), std::invalid_argument);
    CHECK_THROWS_AS(VirtualCoupling(-5, 1), std::invalid_argument);
    CHECK_THROWS_AS(VirtualCoupling(100, -1), std::invalid_argument);
    CHECK_NOTHROW(VirtualCoupling(100, 0));
}

TEST_CASE("The force felt is zero until the simulation publishes, then uses the latest tool sample", "[VirtualCoupling]") {
    VirtualCoupling c(100, 1);
    std::uint64_t seq = 99;
    CHECK(c.forceFelt(Vec3(1, 0, 0), Vec3::Zero(), &seq) == Vec3::Zero());
    CHECK(seq == 0);
    c.publishTool(Vec3(0.9, 0, 0), Vec3(0, 1, 0), Vec3(3, 0, 0));
    c.publishTool(Vec3(0.8, 0, 0), Vec3(0, 2, 0), Vec3(4, 0, 0));
    CHECK(c.forceFelt(Vec3(1, 0, 0), Vec3::Zero(), &seq).isApprox(Vec3(-100 * 0.2, 2, 0), 1e-14));
    CHECK(seq == 2);
    CHECK(c.tool().force == Vec3(4, 0, 0));
    c.publishDevice(Vec3(1, 2, 3), Vec3(4, 5, 6));
    const CouplingSample d = c.device();
    CHECK(d.position == Vec3(1, 2, 3));
    CHECK(d.velocity == Vec3(4, 5, 6));
    CHECK(d.sequence == 1);
}

TEST_CASE("Samples published on one thread are read whole on another", "[VirtualCoupling]") {
    // every published sample has all nine numbers equal to its sequence number: a torn copy (half
    // of one sample, half of the next) would show two different numbers
    VirtualCoupling c(100, 1);
    std::atomic<bool> done{false};
    std::thread writer([&] {
        for (int i = 1; i <= 1000000; ++i) {
            const double s = i;
            c.publishTool(Vec3(s, s, s), Vec3(s, s, s), Vec3(s, s, s));
            c.publishDevice(Vec3(s, s, s), Vec3(s, s, s));
        }
        done = true;
    });
    long torn = 0, reads = 0;
    std::uint64_t last = 0;
    bool ordered = true;
    while (!done || reads == 0) {
        const CouplingSample t = c.tool(), d = c.device();
        ++reads;
        for (const CouplingSample* x : {&t, &d}) {
            if (x->sequence == 0) continue;
            const double s = double(x->sequence);
            if (!(x->position.array() == s).all() || !(x->velocity.array() == s).all()) ++torn;
        }
        if (t.sequence == 0) continue;
        if (!(t.force.array() == double(t.sequence)).all()) ++torn;
        ordered = ordered && t.sequence >= last;
        last = t.sequence;
    }
    writer.join();
    CHECK(reads > 0);
    CHECK(torn == 0);
    CHECK(ordered);
    CHECK(c.tool().sequence == 1000000);
}

TEST_CASE("The proxy low-passes the contact force over the filter time and settles on the balance point", "[VirtualCoupling]") {
    const Vec3 xd(0, 0, 0.05), contact(0, 0, 2.0);
    const double dt = 1e-4;
    SECTION("without a filter the proxy is the balance point at once") {
        VirtualCoupling c(500, 1, 0);
        CHECK(c.proxy(xd, contact, dt) == c.toolTarget(xd, contact));
    }
    SECTION("with a filter of 5 ms, one step moves it dt / (T + dt) of the way, 50 ms nearly all of it") {
        VirtualCoupling c(500, 1, 0.005);
        const Vec3 first = c.proxy(xd, contact, dt);
        CHECK(first[2] == Approx(0.05 + dt / (0.005 + dt) * 2.0 / 500).epsilon(1e-14));
        CHECK(c.filteredContact()[2] == Approx(dt / (0.005 + dt) * 2.0).epsilon(1e-14));
        Vec3 x = first;
        for (int i = 1; i < 500; ++i) x = c.proxy(xd, contact, dt);  // 10 time constants
        // the filter's state after n steps: F (1 - r^n), r = T / (T + dt)
        CHECK(x[2] == Approx(0.05 + (1 - std::pow(0.005 / (0.005 + dt), 500)) * 2.0 / 500).epsilon(1e-12));
        CHECK(x[2] == Approx(0.05 + 2.0 / 500).epsilon(1e-5));
        // the force felt there balances the filtered contact force
        CHECK(c.force(xd, Vec3::Zero(), x, Vec3::Zero()).isApprox(c.filteredContact(), 1e-12));
    }
    CHECK_THROWS_AS(VirtualCoupling(100, 1, -0.001), std::invalid_argument);
}

TEST_CASE("A coupling saved and restored continues bitwise: the filter state and both samples", "[VirtualCoupling]") {
    const double dt = 1e-4;
    // a contact force and a device that change every step
    auto contactAt = [](int k) { return Vec3(0.01 * k, -0.5, 2.0 + std::sin(0.1 * k)); };
    auto deviceAt = [](int k) { return Vec3(0.001 * k, 0, 0.05 - 1e-5 * k); };
    auto stepOnce = [&](VirtualCoupling& c, int k) {
        c.publishDevice(deviceAt(k), Vec3(0.01, 0, -0.001));
        const Vec3 x = c.proxy(c.device().position, contactAt(k), dt);
        c.publishTool(x, Vec3(0, 0, 0.001 * k), contactAt(k));
        return c.forceFelt(deviceAt(k), Vec3::Zero());
    };
    VirtualCoupling straight(500, 1, 0.005), first(500, 1, 0.005), second(500, 1, 0.005);
    for (int k = 0; k < 100; ++k) stepOnce(straight, k), stepOnce(first, k);
    fascia::core::StateWriter out;
    first.saveState(out);
    fascia::core::StateReader in(out.bytes(), 0, out.bytes().size(), "coupling.state");
    second.restoreState(in);
    CHECK(in.atEnd());
    CHECK(second.filteredContact() == first.filteredContact());
    CHECK(second.tool().sequence == 100);
    CHECK(second.device().sequence == 100);
    Vec3 a, b;
    for (int k = 100; k < 200; ++k) a = stepOnce(straight, k), b = stepOnce(second, k);
    CHECK(a == b);
    CHECK(second.filteredContact() == straight.filteredContact());
    CHECK(second.tool().position == straight.tool().position);
    // without the restore the filter starts from zero: another force
    VirtualCoupling fresh(500, 1, 0.005);
    for (int k = 100; k < 200; ++k) b = stepOnce(fresh, k);
    CHECK(a != b);
}
