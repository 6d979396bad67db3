// The stress an observer writes is the stress of the state it writes, viscous history included: a
// Monitor's von Mises column against a fresh evaluation, in this test, of the relaxed stress on the
// positions of each step, for HEMLForceField and TLEDForceField under an explicit integrator
// (forces at the start of each step) and DynamicRelaxation (forces at the end of each load step),
// with a two-term Prony series, at large strain, along a run whose last step is shortened to end on
// its end time (fascia/viscoelastic/HistoryClock.h).
//
// The reference (TLED eq. (24), (30), HEML eq. (18)-(20)): the second Piola-Kirchhoff stress of each
// element is S = S_iso + S_vol - sum_i Y_i, with, at the m-th state written (time t_m),
//   Y_i^m = A_i(t_m - t_(m-1)) R^m + B_i(t_m - t_(m-1)) Y_i^(m-1),   Y_i^0 = A_i(dt) R^0 (0 at rest),
// A_i(h) = h alpha_i / (h + tau_i), B_i(h) = tau_i / (h + tau_i), R the relaxed part (apply) of S at
// that state; the Cauchy stress F S F^T / J and its von Mises stress. The laws' S in closed form:
//   NeoHookean W = mu/2 (I1bar - 3) + kappa/2 (J - 1)^2 (fascia/materials/NeoHookean.h):
//     S_iso = mu J^(-2/3) (I - I1/3 C^-1),   S_vol = kappa (J - 1) J C^-1;
//   CompressibleNeoHookean W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, split so that each part is
//   stress-free at rest (fascia/materials/RelaxationSplit.h: mu/2 (I1 - 3) - mu ln J and lambda/2 (ln J)^2):
//     S_iso = mu (I - C^-1),   S_vol = lambda ln J C^-1.
// Before this test the output lagged: TLED took a static solver's load step for a later time when
// its t + dt and the simulation's t0 + n dt differed in the last bit, and applied one more step of
// relaxation; HEML's von Mises had no viscous part at all.
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using fascia::Mat3;
using fascia::Vec3;
using fascia::core::Simulation;
namespace fs = std::filesystem;

namespace {

struct Law {
    std::string xml;  ///< the material element
    bool neoHookean;  ///< NeoHookean (else CompressibleNeoHookean)
    double a, b;      ///< NeoHookean mu, kappa; CompressibleNeoHookean mu, lambda (Pa)
};

/// S_iso and S_vol of the law at F (see the top of this file).
void splitStress(const Law& law, const Mat3& F, Mat3& Siso, Mat3& Svol) {
    const Mat3 I = Mat3::Identity(), C = F.transpose() * F, Ci = C.inverse();
    const double J = F.determinant(), I1 = C.trace();
    if (law.neoHookean) {
        Siso = law.a * std::pow(J, -2.0 / 3.0) * (I - I1 / 3 * Ci);
        Svol = law.b * (J - 1) * J * Ci;
    } else {
        Siso = law.a * (I - Ci);
        Svol = law.b * std::log(J) * Ci;
    }
}

double vonMises(const Mat3& s) {
    const Mat3 d = s - s.trace() / 3 * Mat3::Identity();
    return std::sqrt(1.5 * (d.array() * d.array()).sum());
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) out.push_back(c);
    return out;
}

} // namespace

TEST_CASE("the stress a monitor writes is the relaxed stress of the state it writes with both force fields and integrator kinds",
          "[Monitor][HEMLForceField][TLEDForceField][DynamicRelaxation][SemiImplicitEuler][ViscoelasticProny]") {
    const std::string ff = GENERATE(as<std::string>{}, "HEMLForceField", "TLEDForceField");
    const std::string integrator = GENERATE(as<std::string>{}, "DynamicRelaxation", "SemiImplicitEuler");
    struct Case {
        Law law;
        std::string apply;
    };
    const Law nh{R"(<NeoHookean name="mat" mu="3000" kappa="8000"/>)", true, 3000, 8000};
    // E = 7800, nu = 0.3: mu = E / (2 (1 + nu)) = 3000, lambda = E nu / ((1 + nu)(1 - 2 nu)) = 4500
    const Law cnh{R"(<CompressibleNeoHookean name="mat" youngModulus="7800" poissonRatio="0.3"/>)", false, 3000, 4500};
    const Case c = GENERATE_COPY(Case{nh, "both"}, Case{nh, "isochoric"}, Case{nh, "volumetric"}, Case{cnh, "isochoric"});
    CAPTURE(ff, integrator, c.law.xml, c.apply);
    const double dt = 0.002, T = 0.0311;  // 15 steps of dt, then one of 0.0011 s
    const std::vector<double> alpha = {0.3, 0.2}, tau = {0.01, 0.04};
    const std::string xml = R"(<Node name="root" dt="0.002">
  <GridMesh name="grid" min="0 0 0" max="0.1 0.1 0.1" resolution="1 1 1" element="tetrahedra6"/>
  <MechanicalObject name="state"/>
  <LumpedMass density="1000"/>
  )" + c.law.xml + R"(
  <ViscoelasticProny name="visco" alpha="0.3 0.2" tau="0.01 0.04" apply=")" + c.apply + R"("/>
  <)" + ff + R"( name="ff"/>
  <)" + integrator + R"( name="solver"/>
  <FixedConstraint name="xmin" group="xmin" directions="1 0 0"/>
  <FixedConstraint name="ymin" group="ymin" directions="0 1 0"/>
  <FixedConstraint name="zmin" group="zmin" directions="0 0 1"/>
  <PrescribedDisplacement name="top" group="zmax" displacement="0 0 0.03" curve="ramp 0.02" directions="0 0 1"/>
  <Monitor name="mon" elements="0 1 2 3 4 5" elementFields="vonMises" residual="true"/>
</Node>)";
    const fs::path dir = fs::temp_directory_path() / ("fascia-stress-output-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    // the run: the positions and the time of every state written
    std::vector<std::vector<Vec3>> states;
    std::vector<double> times;
    fascia::Tetrahedra tets;
    std::vector<Vec3> rest;
    {
        auto sim = Simulation::fromString(xml, "scene.xml", ".", {dir.string(), 0});
        auto& s = sim->state("state");
        auto* f = dynamic_cast<fascia::core::BaseForceField*>(sim->find("ff"));
        REQUIRE(f);
        REQUIRE(f->tetrahedra());
        tets = *f->tetrahedra();
        rest.assign(s.x0().begin(), s.x0().end());
        sim->start();
        const auto record = [&] {
            states.emplace_back(s.x().begin(), s.x().end());
            times.push_back(sim->time());
        };
        record();
        while (sim->time() < T) {
            sim->stepToward(T);
            record();
        }
        sim->finish();
    }
    REQUIRE(times.size() == 17);
    REQUIRE(times.back() == T);
    // the monitor's rows: time, residual, vonMises[0..5]
    std::ifstream in(dir / "mon.csv");
    std::vector<std::vector<std::string>> rows;
    for (std::string l; std::getline(in, l);) rows.push_back(split(l));
    REQUIRE(rows.size() == 1 + times.size());
    const std::vector<std::string>& head = rows[0];
    size_t first = 0;
    while (first < head.size() && head[first].rfind("vonMises[0]", 0) != 0) ++first;
    REQUIRE(first + 6 == head.size());

    // the reference, state by state
    const size_t ne = tets.size();
    std::vector<std::vector<Mat3>> Y(ne, std::vector<Mat3>(alpha.size(), Mat3::Zero()));
    double worst = 0, largest = 0, largestViscous = 0;
    for (size_t m = 0; m < times.size(); ++m) {
        const double h = m == 0 ? dt : times[m] - times[m - 1];
        CAPTURE(m, times[m]);
        REQUIRE(std::stod(rows[1 + m][0]) == Approx(times[m]).epsilon(1e-11));
        for (size_t e = 0; e < ne; ++e) {
            const auto& t = tets[e];
            Mat3 Dx, DX;
            for (int k = 0; k < 3; ++k) {
                Dx.col(k) = states[m][size_t(t[k + 1])] - states[m][size_t(t[0])];
                DX.col(k) = rest[size_t(t[k + 1])] - rest[size_t(t[0])];
            }
            const Mat3 F = Dx * DX.inverse();
            Mat3 Siso, Svol;
            splitStress(c.law, F, Siso, Svol);
            const Mat3 R = (c.apply != "volumetric" ? Siso : Mat3::Zero()) + (c.apply != "isochoric" ? Svol : Mat3::Zero());
            Mat3 S = Siso + Svol, sumY = Mat3::Zero();
            for (size_t i = 0; i < alpha.size(); ++i) {
                Y[e][i] = h * alpha[i] / (h + tau[i]) * R + tau[i] / (h + tau[i]) * Y[e][i];
                sumY += Y[e][i];
            }
            S -= sumY;
            const double J = F.determinant();
            const double expected = vonMises(F * S * F.transpose() / J);
            const double written = std::stod(rows[1 + m][first + e]);
            worst = std::max(worst, std::abs(written - expected));
            largest = std::max(largest, expected);
            largestViscous = std::max(largestViscous, vonMises(F * sumY * F.transpose() / J));
        }
    }
    CAPTURE(worst, largest, largestViscous);
    // the history matters: the viscous part is a good fraction of the stress
    CHECK(largestViscous > 1e-2 * largest);
    CHECK(worst < 1e-9 * largest);
    fs::remove_all(dir);
}
