#pragma once
// Independent references for the hyperelastic laws, for the tests of the materials, HEML and TLED
// plugins. Nothing here calls the materials plugin's law code: each energy is its paper formula
// written from F (through C = F^T F and the modified tensor Cbar = J^(-2/3) C), with std::pow and
// std::log, and the first Piola-Kirchhoff stress is P = dW/dF by fourth-order central differences
// of that energy. The nodal forces of a linear tetrahedron are the direct finite-element ones,
// f_a = -V P dN_a/dX.
//
// Formulas (the same conventions as the documentation of plugins/materials/include/fascia/materials/Laws.h):
//   StVenantKirchhoff (HEML Table 3)          W = lambda/2 (tr E)^2 + mu tr(E^2), E = (C - I)/2
//   IncompressibleNeoHookean (HEML Table 3)   W = C1 (I1 - 3)
//   IncompressibleMooneyRivlin (HEML Table 3) W = C1 (I1 - 3) + C2 (I2 - 3)
//   CompressibleNeoHookean (HEML eq. (26))    W = C1 (I1 - 3) - mu ln J + lambda/2 (ln J)^2
//   CompressibleMooneyRivlin                  W = C1 (tr Cbar - 3) + C2 (I2(Cbar) - 3) + kappa/2 (J - 1)^2
//   NeoHookean (TLED eq. (31)-(32))           W = mu/2 (tr Cbar - 3) + kappa/2 (J - 1)^2
//   TransverselyIsotropic (TLED eq. (33))     W = NeoHookean + eta/4 (a0.Cbar a0 - 1)^2
//   Orthotropic (TLED section 3.2.3)          W = TransverselyIsotropic + eta2/4 (b0.Cbar b0 - 1)^2
// Flat and inverted elements (HEML section 4.4): below J0 the isochoric part (everything but the
// pure-J term) is taken with J0 in place of J, and the pure-J term continues along its second-order
// Taylor polynomial at J0.
#include "fascia/base/Types.h"

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace lawref {

using fascia::Mat3;
using fascia::Positions;
using fascia::Tetrahedra;
using fascia::Vec3;

/// One law with its parameters (Pa) and fibre directions (need not be unit: normalised here, as the
/// materials normalise their `direction` parameters).
struct LawSpec {
    std::string type;
    double lambda = 0, mu = 0, C1 = 0, C2 = 0, kappa = 0, eta = 0, eta2 = 0;
    Vec3 a0 = Vec3(0, 0, 1), b0 = Vec3(1, 0, 0);

    /// The component's parameters as XML attribute strings (name, value).
    std::vector<std::pair<std::string, std::string>> params() const {
        auto num = [](double v) {
            std::ostringstream os;
            os << std::setprecision(17) << v;
            return os.str();
        };
        auto vec = [&](const Vec3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); };
        if (type == "StVenantKirchhoff") return {{"lambda", num(lambda)}, {"mu", num(mu)}};
        if (type == "IncompressibleNeoHookean") return {{"C1", num(C1)}};
        if (type == "IncompressibleMooneyRivlin") return {{"C1", num(C1)}, {"C2", num(C2)}};
        if (type == "CompressibleNeoHookean") return {{"C1", num(C1)}, {"mu", num(mu)}, {"lambda", num(lambda)}};
        if (type == "CompressibleMooneyRivlin") return {{"C1", num(C1)}, {"C2", num(C2)}, {"kappa", num(kappa)}};
        if (type == "NeoHookean") return {{"mu", num(mu)}, {"kappa", num(kappa)}};
        if (type == "TransverselyIsotropic")
            return {{"mu", num(mu)}, {"kappa", num(kappa)}, {"eta", num(eta)}, {"direction", vec(a0)}};
        return {{"mu", num(mu)}, {"kappa", num(kappa)}, {"eta", num(eta)}, {"eta2", num(eta2)},
                {"direction", vec(a0)}, {"direction2", vec(b0)}};
    }
    bool hasFibre() const { return type == "TransverselyIsotropic" || type == "Orthotropic"; }
    bool hasFibre2() const { return type == "Orthotropic"; }
};

/// Off-axis fibre directions: a0 along (1, 2, 3) and b0 along (3, 0, -1), orthogonal to it.
inline Vec3 offAxisA() { return Vec3(1, 2, 3); }
inline Vec3 offAxisB() { return Vec3(3, 0, -1); }

/// Every built-in law with soft-tissue-like parameters (CompressibleNeoHookean with C1 = mu/2, its
/// stress-free value) and off-axis fibres.
inline std::vector<LawSpec> allLaws() {
    std::vector<LawSpec> v(8);
    v[0].type = "StVenantKirchhoff", v[0].lambda = 4000, v[0].mu = 1100;
    v[1].type = "IncompressibleNeoHookean", v[1].C1 = 500;
    v[2].type = "IncompressibleMooneyRivlin", v[2].C1 = 400, v[2].C2 = 150;
    v[3].type = "CompressibleNeoHookean", v[3].C1 = 500, v[3].mu = 1000, v[3].lambda = 4000;
    v[4].type = "CompressibleMooneyRivlin", v[4].C1 = 400, v[4].C2 = 150, v[4].kappa = 20000;
    v[5].type = "NeoHookean", v[5].mu = 1000, v[5].kappa = 20000;
    v[6].type = "TransverselyIsotropic", v[6].mu = 1000, v[6].kappa = 20000, v[6].eta = 3000;
    v[7].type = "Orthotropic", v[7].mu = 1000, v[7].kappa = 20000, v[7].eta = 3000, v[7].eta2 = 1700;
    for (auto& s : v) {
        s.a0 = offAxisA();
        s.b0 = offAxisB();
    }
    return v;
}

inline LawSpec lawNamed(const std::string& type) {
    for (const LawSpec& s : allLaws())
        if (s.type == type) return s;
    return {};
}

/// The isochoric part of W (everything but the pure-J term), with Jc in place of det F.
inline double isochoricW(const LawSpec& s, const Mat3& F, double Jc, const Vec3& a0u, const Vec3& b0u) {
    const Mat3 C = F.transpose() * F;
    const Mat3 I = Mat3::Identity();
    if (s.type == "StVenantKirchhoff") {
        const Mat3 E = 0.5 * (C - I);
        return 0.5 * s.lambda * E.trace() * E.trace() + s.mu * (E * E).trace();
    }
    const double I1 = C.trace(), I2 = 0.5 * (I1 * I1 - (C * C).trace());
    if (s.type == "IncompressibleNeoHookean") return s.C1 * (I1 - 3);
    if (s.type == "IncompressibleMooneyRivlin") return s.C1 * (I1 - 3) + s.C2 * (I2 - 3);
    if (s.type == "CompressibleNeoHookean") return s.C1 * (I1 - 3);
    const Mat3 Cb = std::pow(Jc, -2.0 / 3.0) * C;  // modified right Cauchy-Green tensor
    const double I1b = Cb.trace();
    if (s.type == "CompressibleMooneyRivlin") {
        const double I2b = 0.5 * (I1b * I1b - (Cb * Cb).trace());
        return s.C1 * (I1b - 3) + s.C2 * (I2b - 3);
    }
    double W = 0.5 * s.mu * (I1b - 3);
    if (s.hasFibre()) {
        const double I4b = a0u.dot(Cb * a0u);
        W += 0.25 * s.eta * (I4b - 1) * (I4b - 1);
    }
    if (s.hasFibre2()) {
        const double I6b = b0u.dot(Cb * b0u);
        W += 0.25 * s.eta2 * (I6b - 1) * (I6b - 1);
    }
    return W;
}

/// The pure-J part of W and its first two derivatives at J > 0.
inline void volumetricW(const LawSpec& s, double J, double& W, double& dW, double& d2W) {
    W = dW = d2W = 0;
    if (s.type == "CompressibleNeoHookean") {
        const double L = std::log(J);
        W = -s.mu * L + 0.5 * s.lambda * L * L;
        dW = (-s.mu + s.lambda * L) / J;
        d2W = (s.mu + s.lambda - s.lambda * L) / (J * J);
    } else if (s.type == "CompressibleMooneyRivlin" || s.type == "NeoHookean" || s.type == "TransverselyIsotropic" ||
               s.type == "Orthotropic") {
        W = 0.5 * s.kappa * (J - 1) * (J - 1);
        dW = s.kappa * (J - 1);
        d2W = s.kappa;
    }
}

/// Which parts of W: both, the isochoric one only, or the pure-J one only.
enum class Part { All, Isochoric, Volumetric };

/// W(F) (J per m^3 of reference volume) with the HEML section 4.4 treatment below J0.
inline double energy(const LawSpec& s, const Mat3& F, double J0 = 0.4, Part part = Part::All) {
    const double J = F.determinant();
    const Vec3 a = s.a0.normalized(), b = s.b0.normalized();
    double W = 0;
    if (part != Part::Volumetric) W += isochoricW(s, F, std::max(J, J0), a, b);
    if (part != Part::Isochoric) {
        double Wv, dWv, d2Wv;
        if (J >= J0) {
            volumetricW(s, J, Wv, dWv, d2Wv);
            W += Wv;
        } else {
            volumetricW(s, J0, Wv, dWv, d2Wv);
            const double d = J - J0;
            W += Wv + dWv * d + 0.5 * d2Wv * d * d;
        }
    }
    return W;
}

/// P = dW/dF by fourth-order central differences of energy() (step 1e-4 on each entry of F; keep
/// det F more than 1e-3 away from J0, where the isochoric part has a kink).
inline Mat3 stressP(const LawSpec& s, const Mat3& F, double J0 = 0.4, Part part = Part::All) {
    const double h = 1e-4;
    Mat3 P;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            auto W = [&](double d) {
                Mat3 G = F;
                G(i, j) += d;
                return energy(s, G, J0, part);
            };
            P(i, j) = (8 * (W(h) - W(-h)) - (W(2 * h) - W(-2 * h))) / (12 * h);
        }
    return P;
}

/// Direct finite-element forces of linear tetrahedra: per element F = v V^-1 (edge matrices of the
/// deformed and rest element), P from stressP (or from `Pof`), f_a = -Vol P dN_a/dX with dN_a/dX the
/// rows of V^-1 (a = 1, 2, 3) and dN_0/dX = -(their sum). `lawOf(e)` gives element e's law (its
/// fibre directions included).
inline Positions tetForces(const Positions& X, const Tetrahedra& tets, const Positions& x,
                           const std::function<LawSpec(size_t)>& lawOf, double J0 = 0.4, Part part = Part::All) {
    Positions f(x.size(), Vec3::Zero());
    for (size_t e = 0; e < tets.size(); ++e) {
        const auto& t = tets[e];
        Mat3 V, v;
        for (int k = 0; k < 3; ++k) {
            V.col(k) = X[size_t(t[k + 1])] - X[size_t(t[0])];
            v.col(k) = x[size_t(t[k + 1])] - x[size_t(t[0])];
        }
        const Mat3 Vi = V.inverse();
        const Mat3 P = stressP(lawOf(e), v * Vi, J0, part);
        const double vol = std::abs(V.determinant()) / 6;
        Vec3 g0 = Vec3::Zero();
        for (int k = 0; k < 3; ++k) {
            const Vec3 g = Vi.row(k).transpose();
            f[size_t(t[k + 1])] -= vol * P * g;
            g0 -= g;
        }
        f[size_t(t[0])] -= vol * P * g0;
    }
    return f;
}

/// Largest |a_i - b_i| over the nodes relative to the largest |b_i|.
inline double relativeDifference(const Positions& a, const Positions& b) {
    double d = 0, s = 0;
    for (size_t i = 0; i < b.size(); ++i) {
        d = std::max(d, (a[i] - b[i]).norm());
        s = std::max(s, b[i].norm());
    }
    return s > 0 ? d / s : d;
}

/// A unit direction per element, off every axis and different from element to element, and a second
/// one orthogonal to it (for fibre cell arrays: 3 numbers per element, deliberately not unit length).
inline void elementFibres(size_t n, std::vector<double>& a, std::vector<double>& b) {
    a.clear();
    b.clear();
    for (size_t e = 0; e < n; ++e) {
        const double t = 0.37 * double(e) + 0.2;
        const Vec3 d(std::cos(t), 0.8 * std::sin(1.3 * t) + 0.3, 0.6 + 0.25 * std::cos(0.7 * t));
        Vec3 o = d.cross(Vec3(0.3, -0.5, 0.8));  // orthogonal to d, off the axes
        o *= 1.7 / o.norm();
        const Vec3 dd = 2.5 * d;
        a.insert(a.end(), {dd.x(), dd.y(), dd.z()});
        b.insert(b.end(), {o.x(), o.y(), o.z()});
    }
}

inline Vec3 fibreOf(const std::vector<double>& arr, size_t e) { return Vec3(arr[3 * e], arr[3 * e + 1], arr[3 * e + 2]); }

} // namespace lawref
