#pragma once
/// Conformance harness for materials and element force fields (docs/design.md, conformance).
/// Header-only, so that out-of-tree plugins and tests can call it without linking anything but
/// fascia_core. Every function returns numbers; the caller (a Catch2 test) decides the tolerance.
///
/// (a) Law level, on any BaseMaterial (built-in or user law):
///     - checkLawDerivatives: dI1, dI2, dI4, dI6, dJiso + dJvol against central differences of W
///       in each invariant (the invariants are independent arguments of W(I1, I2, J, I4, I6));
///     - restStressResidual: S = 2 dW/dC at C = I, i.e. |dI1 + 2 dI2 + (dJiso + dJvol)/2| + |dI4| + |dI6|,
///       relative to the shear modulus. It vanishes for stress-free laws; the HEML paper's
///       "incompressible" laws (IncompressibleNeoHookean, IncompressibleMooneyRivlin, Table 3) have
///       no pressure term and are NOT stress-free at rest, and neither is CompressibleNeoHookean with
///       C1 != mu/2 (HEML eq. (26)): BaseMaterial::stressFreeAtRest() says which; test accordingly.
///     - energyJumpAtJ0: continuity of W across the J0 branch of evaluateLaw (HEML section 4.4).
/// (b) Force-field level, on any BaseForceField acting on a BaseMechanicalState:
///     checkForceField deforms the state (an affine map of the rest positions plus a random
///     perturbation), then measures
///     - addForce against -dE/dx by central differences of potentialEnergy(),
///     - the force at rest relative to the force scale of the deformed state,
///     - invariance under a rigid rotation and translation of the deformed configuration
///       (forces must rotate with it, the energy must not change).
///     The state's positions are restored afterwards. Stateful fields (viscoelastic history) must be
///     checked with their history switched off, since the harness calls addForce many times.
/// (c) Rest under relaxation, on a whole simulation: restDrift steps an unloaded body that starts at
///     rest (with its viscous history on) and measures how far it moves and how much the reactions
///     of its constrained nodes change. A body at rest must stay there to round-off with every law
///     and every ViscoelasticProny apply value that the force field accepts (RelaxationSplit.h).
#include "fascia/materials/Material.h"
#include "fascia/sim/Mechanics.h"
#include "fascia/sim/Simulation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace fascia::materials::conformance {

/// A material that is not a Material<Law> (as a user's law is): it forwards to `inner` through the
/// virtual interface, so that a force field runs its generic loop for it. Tests compare that loop
/// with the inlined one of the same law.
struct GenericMaterial : BaseMaterial {
    const BaseMaterial* inner = nullptr;
    unsigned uses() const override { return inner->uses(); }
    void evaluate(const Invariants* in, Response* out, size_t n, double J0) const override { inner->evaluate(in, out, n, J0); }
    double shearModulus() const override { return inner->shearModulus(); }
    double bulkModulus() const override { return inner->bulkModulus(); }
    const Vec3* fibreDirection(int w) const override { return inner->fibreDirection(w); }
    bool stressFreeAtRest() const override { return inner->stressFreeAtRest(); }
};

/// Result of checkLawDerivatives.
struct LawReport {
    double maxRelError = 0;  ///< max over the derivatives of |analytic - central difference| / scale
    std::string worst;       ///< which derivative ("dI1", "dI2", "dJ", "dI4", "dI6")
    double analytic = 0, numeric = 0;  ///< the worst pair
};

/// W and its derivatives at one point, J0 treatment included.
inline Response evaluateOne(const BaseMaterial& m, const Invariants& in, double J0) {
    Response r;
    m.evaluate(&in, &r, 1, J0);
    return r;
}

/// Compares every derivative of the law at `at` to fourth-order central differences of W with the
/// step relStep * max(1, |invariant|). The error of each derivative is relative to
/// max(|analytic|, |numeric|, 1e-6 (shearModulus + bulkModulus)). Keep `at.J` away from J0 by more
/// than twice the step: the isochoric J derivative of split laws jumps there (Material.h).
inline LawReport checkLawDerivatives(const BaseMaterial& m, const Invariants& at, double J0 = 0.4,
                                     double relStep = 1e-4) {
    LawReport rep;
    const Response r = evaluateOne(m, at, J0);
    const double floor = 1e-6 * (std::abs(m.shearModulus()) + std::abs(m.bulkModulus()));
    struct Item {
        const char* name;
        double Invariants::*field;
        double analytic;
    };
    const Item items[] = {{"dI1", &Invariants::I1, r.dI1},
                          {"dI2", &Invariants::I2, r.dI2},
                          {"dJ", &Invariants::J, r.dJiso + r.dJvol},
                          {"dI4", &Invariants::I4, r.dI4},
                          {"dI6", &Invariants::I6, r.dI6}};
    for (const Item& it : items) {
        const double h = relStep * std::max(1.0, std::abs(at.*(it.field)));
        auto Wat = [&](double d) {
            Invariants p = at;
            p.*(it.field) += d;
            return evaluateOne(m, p, J0).W;
        };
        // fourth-order central difference
        const double numeric = (8 * (Wat(h) - Wat(-h)) - (Wat(2 * h) - Wat(-2 * h))) / (12 * h);
        const double scale = std::max({std::abs(it.analytic), std::abs(numeric), floor});
        const double err = std::abs(it.analytic - numeric) / scale;
        if (rep.worst.empty() || err > rep.maxRelError) {
            rep.maxRelError = err;
            rep.worst = it.name;
            rep.analytic = it.analytic;
            rep.numeric = numeric;
        }
    }
    return rep;
}

/// |S| at C = I relative to the shear modulus: |dI1 + 2 dI2 + (dJiso + dJvol)/2| + |dI4| + |dI6|
/// (from S = 2 [dI1 I + dI2 (I1 I - C) + dI4 A0 + dI6 B0] + J dW/dJ C^-1). Zero (to round-off) for
/// stress-free laws.
inline double restStressResidual(const BaseMaterial& m, double J0 = 0.4) {
    const Response r = evaluateOne(m, Invariants{}, J0);
    const double res = std::abs(r.dI1 + 2 * r.dI2 + 0.5 * (r.dJiso + r.dJvol)) + std::abs(r.dI4) + std::abs(r.dI6);
    return res / std::abs(m.shearModulus());
}

/// |W(J0 + eps) - W(J0 - eps)| relative to (shear + bulk modulus) for invariants `at` (J ignored).
inline double energyJumpAtJ0(const BaseMaterial& m, Invariants at, double J0 = 0.4, double eps = 1e-12) {
    at.J = J0 + eps;
    const double a = evaluateOne(m, at, J0).W;
    at.J = J0 - eps;
    const double b = evaluateOne(m, at, J0).W;
    return std::abs(a - b) / (std::abs(m.shearModulus()) + std::abs(m.bulkModulus()));
}

/// Invariants of a deformation gradient F with fibre directions a0, b0 (unit).
inline Invariants invariantsOf(const Mat3& F, const Vec3& a0 = Vec3(0, 0, 1), const Vec3& b0 = Vec3(1, 0, 0)) {
    const Mat3 C = F.transpose() * F;
    Invariants in;
    in.I1 = C.trace();
    in.I2 = 0.5 * (in.I1 * in.I1 - (C * C).trace());
    in.J = F.determinant();
    in.I4 = a0.dot(C * a0);
    in.I6 = b0.dot(C * b0);
    return in;
}

/// Options of checkForceField.
struct ForceFieldCheckOptions {
    /// Deformed state: x = affine * x0 + amplitude * h * (uniform random in [-1, 1]^3 per node),
    /// h the characteristic spacing (bounding-box diagonal / cbrt(nodes)).
    Mat3 affine = (Mat3() << 1.08, 0.05, 0.0, -0.03, 0.94, 0.04, 0.02, 0.0, 1.03).finished();
    double amplitude = 0.05;
    /// Finite-difference step relative to h.
    double relStep = 1e-6;
    /// Nodes whose gradient is checked by finite differences (evenly spread; 0 = all).
    size_t maxNodes = 0;
    unsigned seed = 12345;
    double t = 0.0;
};

/// Result of checkForceField. Every number is relative.
struct ForceFieldReport {
    double forceScale = 0;        ///< max |f_i| in the deformed state (N)
    double gradientError = 0;     ///< max_i |f_i + dE/dx_i| / forceScale (central differences)
    double restForce = 0;         ///< max |f_i| at rest / forceScale
    double rotationError = 0;     ///< max_i |f_i(Rx + c) - R f_i(x)| / forceScale
    double energyRotationError = 0; ///< |E(Rx + c) - E(x)| / |E(x)|
    double energy = 0;            ///< E in the deformed state (J)
    size_t worstNode = 0;         ///< node of the largest gradient error
};

namespace detail {
inline Positions forces(core::BaseForceField& ff, core::BaseMechanicalState& s, double t) {
    Positions f(s.size(), Vec3::Zero());
    ff.addForce(s, f, t);
    return f;
}
inline double maxNorm(const Positions& f) {
    double m = 0;
    for (const Vec3& v : f) m = std::max(m, v.norm());
    return m;
}
} // namespace detail

/// Runs the force-field checks of (b) on the state's rest positions x0; restores x afterwards.
inline ForceFieldReport checkForceField(core::BaseForceField& ff, core::BaseMechanicalState& s,
                                        const ForceFieldCheckOptions& opt = {}) {
    ForceFieldReport rep;
    const size_t n = s.size();
    if (n == 0) return rep;
    const Positions saved = s.x();
    const Positions& X = s.x0();

    // characteristic spacing
    Vec3 lo = X[0], hi = X[0];
    for (const Vec3& p : X) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double h = (hi - lo).norm() / std::max(1.0, std::cbrt(double(n)));

    // deformed configuration
    std::mt19937 rng(opt.seed);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    Positions x(n);
    for (size_t i = 0; i < n; ++i) {
        const Vec3 r(uni(rng), uni(rng), uni(rng));
        x[i] = opt.affine * X[i] + opt.amplitude * h * r;
    }

    // forces and energy there
    s.x() = x;
    const Positions f = detail::forces(ff, s, opt.t);
    rep.energy = ff.potentialEnergy(s);
    rep.forceScale = detail::maxNorm(f);
    const double scale = rep.forceScale > 0 ? rep.forceScale : 1.0;

    // gradient by central differences of the energy
    const double step = opt.relStep * h;
    const size_t stride = (opt.maxNodes == 0 || opt.maxNodes >= n) ? 1 : n / opt.maxNodes;
    for (size_t i = 0; i < n; i += stride) {
        Vec3 g;
        for (int c = 0; c < 3; ++c) {
            s.x()[i][c] = x[i][c] + step;
            const double ep = ff.potentialEnergy(s);
            s.x()[i][c] = x[i][c] - step;
            const double em = ff.potentialEnergy(s);
            s.x()[i][c] = x[i][c];
            g[c] = (ep - em) / (2 * step);
        }
        const double err = (f[i] + g).norm() / scale;
        if (err > rep.gradientError) {
            rep.gradientError = err;
            rep.worstNode = i;
        }
    }

    // rigid motion of the deformed configuration
    const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    const Vec3 c = Vec3(0.3, -0.2, 0.5) * (10 * h);
    for (size_t i = 0; i < n; ++i) s.x()[i] = R * x[i] + c;
    const Positions fr = detail::forces(ff, s, opt.t);
    const double er = ff.potentialEnergy(s);
    for (size_t i = 0; i < n; ++i) rep.rotationError = std::max(rep.rotationError, (fr[i] - R * f[i]).norm() / scale);
    rep.energyRotationError = std::abs(er - rep.energy) / std::max(std::abs(rep.energy), 1e-300);

    // rest
    s.x() = X;
    rep.restForce = detail::maxNorm(detail::forces(ff, s, opt.t)) / scale;

    s.x() = saved;
    return rep;
}

/// Result of restDrift. Every number is relative.
struct RestReport {
    double maxDisplacement = 0;    ///< max over the steps and nodes of |x - x0| / h (h: characteristic spacing)
    double firstReaction = 0;      ///< max |reaction| after the first step / forceScale
    double maxReactionChange = 0;  ///< max over the steps and nodes of |reaction - reaction after step 1| / forceScale
    long steps = 0;                ///< steps run
};

/// Runs `steps` steps of sim, whose state s starts at rest (x = x0, v = 0) with no load, and
/// reports its drift (see RestReport; h is the bounding-box diagonal / cbrt(nodes), forceScale a
/// force in N that the caller chooses, e.g. a modulus times h^2).
inline RestReport restDrift(core::Simulation& sim, core::BaseMechanicalState& s, long steps, double forceScale) {
    RestReport rep;
    const Positions& X = s.x0();
    const size_t n = X.size();
    if (n == 0) return rep;
    Vec3 lo = X[0], hi = X[0];
    for (const Vec3& p : X) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double h = (hi - lo).norm() / std::max(1.0, std::cbrt(double(n)));
    Positions first;
    for (long k = 0; k < steps; ++k) {
        sim.step();
        ++rep.steps;
        for (size_t i = 0; i < n; ++i) rep.maxDisplacement = std::max(rep.maxDisplacement, (s.x()[i] - X[i]).norm() / h);
        const Positions& r = s.reaction();
        if (k == 0) {
            first = r;
            rep.firstReaction = detail::maxNorm(r) / forceScale;
        } else {
            for (size_t i = 0; i < r.size() && i < first.size(); ++i)
                rep.maxReactionChange = std::max(rep.maxReactionChange, (r[i] - first[i]).norm() / forceScale);
        }
    }
    return rep;
}

} // namespace fascia::materials::conformance
