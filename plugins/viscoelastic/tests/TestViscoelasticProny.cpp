// Tests of ViscoelasticProny: parameter checks, TLED eq. (30) coefficients, and the discrete
// recurrence against the exact relaxation function (TLED eq. (7)).
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include "fascia/base/Error.h"
#include "fascia/scene/Node.h"

#include <catch2/catch.hpp>

#include <cmath>

using fascia::viscoelastic::ViscoelasticProny;
namespace core = fascia::core;

namespace {

// a component built in code, its parameters read as from a scene at "scene.xml:<line>"
ViscoelasticProny& makeProny(core::Node& root, const std::string& alpha, const std::string& tau,
                             const std::string& apply = "") {
    auto& p = root.add<ViscoelasticProny>("visco");
    p.setClassName("ViscoelasticProny");
    p.setLoc({"scene.xml", 7});
    p.findParam("alpha")->read(alpha, {"scene.xml", 7});
    p.findParam("tau")->read(tau, {"scene.xml", 7});
    if (!apply.empty()) p.findParam("apply")->read(apply, {"scene.xml", 7});
    return p;
}

std::string initError(ViscoelasticProny& p) {
    try {
        p.init();
    } catch (const core::Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("ViscoelasticProny accepts a valid series and reports its terms", "[ViscoelasticProny]") {
    core::Node root("root");
    auto& p = makeProny(root, "0.5 0.2", "0.58 5", "both");
    REQUIRE_NOTHROW(p.init());
    CHECK(p.termCount() == 2);
    CHECK(p.alpha(1) == 0.2);
    CHECK(p.tau(0) == 0.58);
    CHECK(p.alphaInfinity() == Approx(0.3).epsilon(1e-14));
    CHECK(p.apply() == ViscoelasticProny::Apply::Both);
    CHECK(p.relaxesIsochoric());
    CHECK(p.relaxesVolumetric());
    CHECK_FALSE(p.hasCoefficients());
    // relaxation function, TLED eq. (7): alpha(0) = 1, alpha(inf) = alpha_inf
    CHECK(p.relaxation(0.0) == Approx(1.0).epsilon(1e-15));
    CHECK(p.relaxation(1e4) == Approx(0.3).epsilon(1e-12));
    CHECK(p.relaxation(0.58) == Approx(1 - 0.5 * (1 - std::exp(-1.0)) - 0.2 * (1 - std::exp(-0.58 / 5))).epsilon(1e-14));
}

TEST_CASE("ViscoelasticProny defaults to isochoric relaxation", "[ViscoelasticProny]") {
    core::Node root("root");
    auto& p = makeProny(root, "0.5", "0.58");
    p.init();
    CHECK(p.apply() == ViscoelasticProny::Apply::Isochoric);
    CHECK(p.relaxesIsochoric());
    CHECK_FALSE(p.relaxesVolumetric());
}

TEST_CASE("ViscoelasticProny rejects inconsistent series with located errors", "[ViscoelasticProny]") {
    core::Node root("root");
    SECTION("different lengths") {
        auto& p = makeProny(root, "0.3 0.2", "0.58");
        const std::string msg = initError(p);
        CHECK(msg.find("scene.xml:7: error:") != std::string::npos);
        CHECK(msg.find("tau has 1 entries but alpha has 2") != std::string::npos);
    }
    SECTION("sum of alphas not below 1") {
        auto& p = makeProny(root, "0.6 0.4", "1 2");
        const std::string msg = initError(p);
        CHECK(msg.find("scene.xml:7: error:") != std::string::npos);
        CHECK(msg.find("sum to 1") != std::string::npos);
        CHECK(msg.find("alpha_inf") != std::string::npos);
    }
    SECTION("empty lists") {
        auto& p = makeProny(root, "", "");
        CHECK(initError(p).find("at least one Prony term") != std::string::npos);
    }
}

TEST_CASE("ViscoelasticProny rejects non-positive entries when parsing", "[ViscoelasticProny]") {
    core::Node root("root");
    auto& p = root.add<ViscoelasticProny>("visco");
    p.setClassName("ViscoelasticProny");
    const std::string bad = GENERATE(as<std::string>{}, "0", "-0.1", "1.0", "0.2 nan");
    CAPTURE(bad);
    try {
        p.findParam("alpha")->read(bad, {"scene.xml", 9});
        FAIL("no error for alpha = " << bad);
    } catch (const core::Error& e) {
        CHECK(std::string(e.what()).find("scene.xml:9: error:") != std::string::npos);
        CHECK(std::string(e.what()).find("alpha") != std::string::npos);
    }
    CHECK_THROWS_AS(p.findParam("tau")->read("0.5 -1", {"scene.xml", 9}), core::Error);
    CHECK_THROWS_AS(p.findParam("tau")->read("0", {"scene.xml", 9}), core::Error);
    CHECK_THROWS_AS(p.findParam("apply")->read("deviatoric", {"scene.xml", 9}), core::Error);
}

TEST_CASE("ViscoelasticProny computes the TLED eq. (30) coefficients and recomputes them when dt changes",
          "[ViscoelasticProny]") {
    core::Node root("root");
    auto& p = makeProny(root, "0.5 0.25", "0.58 2");
    p.init();
    p.dtChanged(1e-3);
    REQUIRE(p.hasCoefficients());
    REQUIRE(p.A().size() == 2);
    // A = dt alpha / (dt + tau), B = tau / (dt + tau), written out by hand
    CHECK(p.A()[0] == Approx(0.0005 / 0.581).epsilon(1e-15));
    CHECK(p.B()[0] == Approx(0.58 / 0.581).epsilon(1e-15));
    CHECK(p.A()[1] == Approx(0.00025 / 2.001).epsilon(1e-15));
    CHECK(p.B()[1] == Approx(2.0 / 2.001).epsilon(1e-15));
    CHECK(p.dt() == 1e-3);

    p.dtChanged(0.1);
    CHECK(p.A()[0] == Approx(0.05 / 0.68).epsilon(1e-15));
    CHECK(p.B()[0] == Approx(0.58 / 0.68).epsilon(1e-15));

    // the static form (for HEML eq. (20), same A_i, B_i) agrees with the member form
    std::vector<double> A, B;
    ViscoelasticProny::coefficients({0.5, 0.25}, {0.58, 2.0}, 0.1, A, B);
    CHECK(A == p.A());
    CHECK(B == p.B());
    p.coefficients(1e-3, A, B);
    CHECK(A[0] == Approx(0.0005 / 0.581).epsilon(1e-15));
    CHECK(p.dt() == 0.1);  // computing for another dt leaves the component's own coefficients alone

    CHECK_THROWS_AS(p.dtChanged(0.0), core::Error);
}

TEST_CASE("ViscoelasticProny refuses to update before it has a time step", "[ViscoelasticProny]") {
    core::Node root("root");
    auto& p = makeProny(root, "0.5", "0.58");
    p.init();
    double R = 1, Y = 0, out = 0;
    CHECK_THROWS_AS(p.update(&R, &Y, 1, 1, &out), core::Error);
}

TEST_CASE("ViscoelasticProny's recurrence converges at first order to the exact stress relaxation",
          "[ViscoelasticProny]") {
    // a unit response switched on at t = 0 and held: the exact visco response is the relaxation
    // function alpha(t) (TLED eq. (7)); backward Euler gives alpha_inf + sum alpha_i B_i^n
    core::Node root("root");
    auto& p = makeProny(root, "0.5 0.2", "0.58 0.1");
    p.init();
    auto maxError = [&](double dt) {
        p.dtChanged(dt);
        std::vector<double> Y(2, 0.0);
        double err = 0;
        const long n = std::lround(2.0 / dt);
        for (long k = 0; k <= n; ++k) {
            const double R = 1.0;
            double out = 0;
            p.update(&R, Y.data(), 1, 1, &out);
            // the first update happens at t = 0 with the response already on: Y^0 = A R
            const double t = k * dt;
            err = std::max(err, std::abs(out - p.relaxation(t)));
        }
        return err;
    };
    const double e1 = maxError(1e-3), e2 = maxError(1e-4);
    CAPTURE(e1, e2);
    CHECK(e1 < 5e-3);
    CHECK(e2 < 5e-4);
    CHECK(e1 / e2 == Approx(10).epsilon(0.1));  // first order in dt

    // the long-term limit is exact
    p.dtChanged(0.01);
    std::vector<double> Y(2, 0.0);
    double out = 0;
    const double R = 2.0;
    for (int k = 0; k < 20000; ++k) p.update(&R, Y.data(), 1, 1, &out);
    CHECK(out == Approx(2.0 * p.alphaInfinity()).epsilon(1e-10));
}
