#pragma once
// Closed-form homogeneous solutions for the HEML verification tests (laterally free uniaxial
// loading of HEML section 5.1, confined compression through J0 of section 4.4). Written from the
// laws' definitions, independently of the materials plugin. l: stretch along z, lt: lateral stretch.
#include <cmath>

namespace hemltest::analytic {

/// Saint Venant-Kirchhoff, laterally free uniaxial load along z (HEML section 5.1):
/// S_xx = lambda tr E + 2 mu E_xx = 0 gives E_xx = -nu E_zz, nu = lambda / (2 (lambda + mu)), so
///   lt = sqrt(1 - nu (l^2 - 1)),  S_zz = Y E_zz,  P_zz = l S_zz = mu (3 lambda + 2 mu) / (2 (lambda + mu)) (l^3 - l).
struct SvkUniaxial {
    double lt, J, Pzz;
};
inline SvkUniaxial svkUniaxial(double lambda, double mu, double l) {
    const double nu = lambda / (2 * (lambda + mu));
    SvkUniaxial r;
    r.lt = std::sqrt(1 - nu * (l * l - 1));
    r.J = l * r.lt * r.lt;
    r.Pzz = mu * (3 * lambda + 2 * mu) / (2 * (lambda + mu)) * (l * l * l - l);
    return r;
}

/// Compressible neo-Hookean of HEML eq. (26), W = C1 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, so
/// S = 2 C1 I + (lambda ln J - mu) C^-1. Laterally free uniaxial load along z, F = diag(lt, lt, l):
/// S_xx = 0  <=>  r(lt) = 2 C1 lt^2 + lambda ln(l lt^2) - mu = 0, solved by Newton (r' = 4 C1 lt + 2 lambda / lt);
/// then P_zz = l S_zz = 2 C1 l + (lambda ln J - mu) / l.
struct NhUniaxial {
    double lt, J, Pzz;
    int iterations;
};
inline NhUniaxial compressibleNeoHookeanUniaxial(double C1, double mu, double lambda, double l) {
    NhUniaxial r{1.0, l, 0.0, 0};
    for (int it = 0; it < 100; ++it) {
        const double res = 2 * C1 * r.lt * r.lt + lambda * std::log(l * r.lt * r.lt) - mu;
        const double dres = 4 * C1 * r.lt + 2 * lambda / r.lt;
        const double step = res / dres;
        r.lt -= step;
        r.iterations = it + 1;
        if (std::abs(step) < 1e-15 * r.lt) break;
    }
    r.J = l * r.lt * r.lt;
    r.Pzz = 2 * C1 * l + (lambda * std::log(r.J) - mu) / l;
    return r;
}

/// dW_vol/dJ of eq. (26) with the J0 treatment of HEML section 4.4: below J0 the derivative
/// continues along its tangent at J0 (the energy along its second-order Taylor polynomial).
inline double nhVolumetricDerivative(double mu, double lambda, double J, double J0) {
    if (J >= J0) return (lambda * std::log(J) - mu) / J;
    const double d1 = (lambda * std::log(J0) - mu) / J0;
    const double d2 = (lambda - lambda * std::log(J0) + mu) / (J0 * J0);
    return d1 + d2 * (J - J0);
}

/// Confined compression F = diag(1, 1, l) (J = l) of the eq. (26) law with the J0 treatment:
///   P_zz = 2 C1 l + W_vol'(J),   P_xx = 2 C1 + W_vol'(J) l   (nominal stresses).
struct Confined {
    double Pzz, Pxx;
};
inline Confined compressibleNeoHookeanConfined(double C1, double mu, double lambda, double l, double J0) {
    const double dW = nhVolumetricDerivative(mu, lambda, l, J0);
    return {2 * C1 * l + dW, 2 * C1 + dW * l};
}

} // namespace hemltest::analytic
