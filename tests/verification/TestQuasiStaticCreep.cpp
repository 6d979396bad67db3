// Quasi-static creep: DynamicRelaxation load steps under a constant load with a Prony series (TLED and
// HEML), against the analytic creep curve of linear viscoelasticity (small strain). Each load step
// advances the viscous history once, at the converged solution; advancing it at every iteration would
// relax the cube in a few steps.
//
// The reference: with the whole stress relaxed by g(t) = g_inf + sum_i alpha_i exp(-t / tau_i)
// (apply="both"; fascia/viscoelastic/ViscoelasticProny.h), a constant stress sigma0 applied at t = 0
// gives the strain eps(t) = sigma0 / E D(t), D the creep function of g. With one part relaxed, the
// correspondence principle on 1/E = 1/(3 G) + 1/(9 K) (uniaxial stress) gives the uniaxial creep
// compliance D(t)/(3 mu) + 1/(9 kappa) (apply="isochoric": the shear modulus relaxes by g, the bulk
// modulus does not; NeoHookean's isochoric part is its mu part at small strain) and
// 1/(3 mu) + D(t)/(9 kappa) (apply="volumetric"). In Laplace space
// s g^(s) . s D^(s) = 1; with h(s) = s g^(s) = g_inf + sum_i alpha_i s / (s + beta_i), beta_i = 1/tau_i,
// D^(s) = 1 / (s h(s)), whose poles are s = 0 (residue 1 / g_inf) and the N roots s = -r_k of h, one
// in each interval (beta_(k-1), beta_k) of r (beta_0 = 0): D(t) = 1/g_inf + sum_k exp(-r_k t) / (-r_k h'(-r_k)),
// h'(s) = sum_i alpha_i beta_i / (s + beta_i)^2.
#include "StaticSupport.h"

#include <algorithm>
#include <cstdio>
#include <vector>

using namespace statics;

namespace {

/// The creep function D(t) of a Prony relaxation function (g(0) = 1), from its Laplace transform.
class CreepFunction {
public:
    CreepFunction(std::vector<double> alpha, std::vector<double> tau) : m_alpha(std::move(alpha)) {
        m_ginf = 1;
        for (double a : m_alpha) m_ginf -= a;
        for (double t : tau) m_beta.push_back(1 / t);
        std::vector<double> sorted = m_beta;
        std::sort(sorted.begin(), sorted.end());
        double lo = 0;
        for (double hi : sorted) {
            // h(-r) goes from + (just above lo) to - infinity (just below hi): bisection
            double a = lo + 1e-14 * hi, b = hi - 1e-14 * hi;
            for (int it = 0; it < 200; ++it) {
                const double m = 0.5 * (a + b);
                (h(-m) > 0 ? a : b) = m;
            }
            m_roots.push_back(0.5 * (a + b));
            lo = hi;
        }
    }
    double operator()(double t) const {
        double d = 1 / m_ginf;
        for (double r : m_roots) d += std::exp(-r * t) / (-r * dh(-r));
        return d;
    }
    double h(double s) const {
        double v = m_ginf;
        for (size_t i = 0; i < m_alpha.size(); ++i) v += m_alpha[i] * s / (s + m_beta[i]);
        return v;
    }

private:
    double dh(double s) const {
        double v = 0;
        for (size_t i = 0; i < m_alpha.size(); ++i) v += m_alpha[i] * m_beta[i] / ((s + m_beta[i]) * (s + m_beta[i]));
        return v;
    }
    std::vector<double> m_alpha, m_beta, m_roots;
    double m_ginf = 1;
};

/// A number as XML text, to the last digit (std::to_string keeps six decimals only).
std::string text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string list(const std::vector<double>& v) {
    std::string s;
    for (double x : v) s += (s.empty() ? "" : " ") + text(x);
    return s;
}

} // namespace

TEST_CASE("The creep function of a Prony series is the one-term closed form and satisfies D(0) g(0) = 1",
          "[ViscoelasticProny]") {
    // one term: D(t) = 1/g_inf - alpha/g_inf exp(-g_inf t / tau)
    const CreepFunction one({0.5}, {1.0});
    for (double t : {0.0, 0.3, 1.0, 4.0}) CHECK(one(t) == Approx(2 - 1 * std::exp(-0.5 * t)).epsilon(1e-13));
    // any series: the instantaneous compliance is 1 / g(0) = 1, the long-term one 1 / g_inf
    const CreepFunction two({0.3, 0.25}, {0.2, 1.5});
    CHECK(two(0) == Approx(1).epsilon(1e-12));
    CHECK(two(1e3) == Approx(1 / 0.45).epsilon(1e-12));
}

TEST_CASE("DynamicRelaxation load steps creep under a constant load as the analytic creep curve",
          "[DynamicRelaxation][ViscoelasticProny][HEMLForceField][TLEDForceField]") {
    struct Series {
        std::vector<double> alpha, tau;
    };
    struct Discretisation {
        std::string ff, element;
    };
    // HEMLForceField has tetrahedra only
    const Discretisation disc = GENERATE(Discretisation{"TLEDForceField", "hexahedra"}, Discretisation{"TLEDForceField", "tetrahedra6"},
                                         Discretisation{"HEMLForceField", "tetrahedra6"});
    const std::string& ff = disc.ff;
    const std::string& element = disc.element;
    const Series series = GENERATE(Series{{0.5}, {1.0}}, Series{{0.3, 0.25}, {0.25, 1.0}});
    const std::string apply = GENERATE(as<std::string>{}, "both", "isochoric", "volumetric");
    CAPTURE(ff, element, series.alpha.size(), apply);
    // the backward-Euler Prony update is first order (relative error about alpha dt / (2 tau)):
    // dt = tau_min / 1000 keeps it below 1e-4
    const double dt = *std::min_element(series.tau.begin(), series.tau.end()) / 1000, T = 2.0;
    // small strain (1e-6): neo-Hookean with E = 9 kappa mu / (3 kappa + mu), uniaxial stress sigma0
    const double mu = 1000, kappa = 5000, E = 9 * kappa * mu / (3 * kappa + mu), sigma0 = 1e-6 * E;
    // the load sigma0 A0 on the top face: shared equally by the four corners of the hexahedron; on the
    // triangles of the tetrahedra, as a (follower, at small strain the same) pressure -sigma0, a third of
    // each triangle's force on each corner, which is what a uniform traction gives linear triangles
    const std::string load = element == "hexahedra"
                                 ? R"(<ConstantForce name="load" group="zmax" totalForce="0 0 )" + text(sigma0) + R"("/>)"
                                 : R"(<SurfacePressure name="load" nodeGroup="zmax" pressure=")" + text(-sigma0) + R"("/>)";
    const std::string xml = R"(<Node name="root" dt=")" + text(dt) + R"(">
  <GridMesh name="grid" min="0 0 0" max="1 1 1" resolution="1 1 1" element=")" + element + R"("/>
  <MechanicalObject name="state"/>
  <LumpedMass density="1000"/>
  <NeoHookean name="mat" mu="1000" kappa="5000"/>
  <ViscoelasticProny name="visco" alpha=")" + list(series.alpha) + R"(" tau=")" + list(series.tau) + R"(" apply=")" + apply + R"("/>
  <)" + ff + R"( name="ff"/>
  <DynamicRelaxation name="dr" tolerance="1e-10" displacementTolerance="1e-10"/>
  <FixedConstraint name="xmin" group="xmin" directions="1 0 0"/>
  <FixedConstraint name="ymin" group="ymin" directions="0 1 0"/>
  <FixedConstraint name="zmin" group="zmin" directions="0 0 1"/>
  )" + load + R"(
</Node>)";
    auto sim = Simulation::fromString(xml);
    REQUIRE(sim->dt() == dt);
    const CreepFunction D(series.alpha, series.tau);
    // uniaxial creep compliance times E (see the top of this file)
    const auto compliance = [&](double t) {
        if (apply == "both") return D(t);
        if (apply == "isochoric") return E * (D(t) / (3 * mu) + 1 / (9 * kappa));
        return E * (1 / (3 * mu) + D(t) / (9 * kappa));
    };
    const auto& s = sim->state("state");
    const long steps = std::lround(T / dt);
    double worst = 0;
    for (long n = 1; n <= steps; ++n) {
        sim->step();
        if (n % (steps / 10) != 0 && n != 1) continue;
        double uz = 0;  // mean top displacement
        int count = 0;
        for (size_t i = 0; i < s.size(); ++i)
            if (s.x0()[i].z() == 1.0) uz += s.x()[i].z() - 1.0, ++count;
        uz /= count;
        const double expected = sigma0 / E * compliance(sim->time());
        CAPTURE(n, sim->time(), uz, expected);
        CHECK(uz == Approx(expected).epsilon(1e-4));
        worst = std::max(worst, std::abs(uz / expected - 1));
    }
    CAPTURE(worst);
    // it did creep, by far more than the tolerance: from the instantaneous compliance 1 (D(0) = 1) by
    // 4 % (volumetric: the bulk modulus is 15 times the shear modulus) to 85 %
    CHECK(compliance(0) == Approx(1).epsilon(1e-12));
    CHECK(compliance(T) - compliance(0) > 0.03);
    for (auto& r : solver(*sim).reports()) REQUIRE(r.converged);
}
