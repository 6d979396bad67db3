#pragma once
// Shared helpers of the static-solver verification tests: scenes solved by DynamicRelaxation and the
// closed forms they are checked against.
#include "DynamicRelaxation.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>

namespace statics {

using fascia::core::Simulation;
using fascia::mechanics::DynamicRelaxation;

inline DynamicRelaxation& solver(Simulation& sim, const std::string& name = "dr") {
    auto* dr = dynamic_cast<DynamicRelaxation*>(sim.find(name));
    REQUIRE(dr);
    return *dr;
}

/// The root of a scalar equation g(x) = 0 by Newton's method with a central-difference slope,
/// from x0; to round-off.
inline double newton(const std::function<double(double)>& g, double x0) {
    double x = x0;
    for (int it = 0; it < 100; ++it) {
        const double h = 1e-6 * std::max(1.0, std::abs(x));
        const double gx = g(x), slope = (g(x + h) - g(x - h)) / (2 * h);
        const double dx = -gx / slope;
        x += dx;
        if (std::abs(dx) < 1e-15 * std::max(1.0, std::abs(x))) break;
    }
    return x;
}

/// Uniaxial stretch lambda along z of the neo-Hookean law W = mu/2 (I1bar - 3) + kappa/2 (J - 1)^2
/// (fascia/materials/NeoHookean.h), laterally free: F = diag(a, a, lambda) with the lateral Cauchy
/// stress zero. Cauchy stress sigma = mu/J dev(bbar) + kappa (J - 1) I, bbar = J^(-2/3) F F^T.
struct UniaxialNeoHookean {
    double a = 1;    ///< lateral stretch
    double Pzz = 0;  ///< first Piola-Kirchhoff stress P_zz = J sigma_zz / lambda (Pa)
    UniaxialNeoHookean(double mu, double kappa, double lambda) {
        auto sigma = [&](double a_, int axis) {
            const double J = a_ * a_ * lambda, s = std::pow(J, -2.0 / 3.0);
            const double I1bar = s * (2 * a_ * a_ + lambda * lambda);
            const double bb = s * (axis == 2 ? lambda * lambda : a_ * a_);
            return mu / J * (bb - I1bar / 3) + kappa * (J - 1);
        };
        a = newton([&](double x) { return sigma(x, 0); }, 1.0);
        Pzz = a * a * lambda * sigma(a, 2) / lambda;
    }
};

/// A unit cube on rollers (xmin, ymin, zmin) stretched along z by a prescribed top displacement.
inline std::string stretchScene(const std::string& forceField, const std::string& element, double stretch,
                                const std::string& solver, const std::string& rootExtra = "dt=\"1\"",
                                const std::string& density = "1000") {
    return R"(<Node name="root" )" + rootExtra + R"(>
  <Node name="cube">
    <GridMesh name="grid" min="0 0 0" max="1 1 1" resolution="3 3 3" element=")" + element + R"("/>
    <MechanicalObject name="state"/>
    <LumpedMass density=")" + density + R"("/>
    <NeoHookean name="mat" mu="1000" kappa="5000"/>
    <)" + forceField + R"( name="ff"/>
    )" + solver + R"(
    <FixedConstraint name="xmin" group="xmin" directions="1 0 0"/>
    <FixedConstraint name="ymin" group="ymin" directions="0 1 0"/>
    <FixedConstraint name="zmin" group="zmin" directions="0 0 1"/>
    <PrescribedDisplacement name="top" group="zmax" displacement="0 0 )" + std::to_string(stretch - 1) + R"(" shape="rampHold" rampTime="1" directions="0 0 1"/>
  </Node>
</Node>)";
}

/// Largest relative deviation of the state from x = diag(a, a, lambda) X.
inline double homogeneousError(const fascia::core::BaseMechanicalState& s, double a, double lambda) {
    double err = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        const auto& X = s.x0()[i];
        const fascia::Vec3 expected(a * X.x(), a * X.y(), lambda * X.z());
        err = std::max(err, (s.x()[i] - expected).norm());
    }
    return err;
}

/// Sum of the z reactions of a constraint's nodes.
inline double reactionZ(Simulation& sim, const std::string& constraint) {
    auto* c = dynamic_cast<fascia::core::BaseConstraint*>(sim.find(constraint));
    REQUIRE(c);
    const auto& r = sim.state("state").reaction();
    double fz = 0;
    for (int i : c->constrainedNodes()) fz += r[static_cast<size_t>(i)].z();
    return fz;
}

} // namespace statics
