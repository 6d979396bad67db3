#pragma once
/// The volumetric parts U(J) a law is composed with (ComposedLaw.h): each is written once here and
/// chosen by a law's type, as FEBio's uncoupled materials take their U(J) from one base.
///
/// Each gives, for J > 0 (evaluateLaw in Material.h continues it below J0 along its tangent, HEML
/// section 4.4), U, dU/dJ and d2U/dJ2 in the scalar T, its parameters as double members converted
/// to T once per call, its formula as text (kEnergy, which the registry's descriptions are built
/// from) and whether it is stress-free at rest (dU/dJ = 0 at J = 1).
#include "fascia/base/Hd.h"
#include "fascia/materials/FastMath.h"

namespace fascia::materials {

/// No volumetric part (the HEML paper's Table 3 laws, Saint Venant-Kirchhoff: all of W is isochoric()).
struct NoVolume {
    static constexpr const char* kEnergy = "";
    static constexpr bool kStressFreeAtRest = true;
    template <class T>
    FASCIA_HD void volumetric(T, T& W, T& dW, T& d2W) const { W = dW = d2W = T(0); }
};

/// U = kappa/2 (J - 1)^2 (TLED eq. (32); HEML eq. (21)-(25)): finite at J = 0, so an element can be
/// crushed flat with a finite energy.
struct QuadraticVolume {
    static constexpr const char* kEnergy = "kappa/2 (J - 1)^2";
    static constexpr bool kStressFreeAtRest = true;
    double kappa = 0;  ///< bulk modulus (Pa)
    template <class T>
    FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const {
        const T kappa = T(this->kappa);
        W = T(0.5) * kappa * (J - T(1)) * (J - T(1));
        dW = kappa * (J - T(1));
        d2W = kappa;
    }
};

/// U = k/2 (ln J)^2 (FEBio's uncoupled materials): grows without bound as J -> 0.
/// dU/dJ = k ln J / J, d2U/dJ2 = k (1 - ln J) / J^2.
struct LogVolume {
    static constexpr const char* kEnergy = "k/2 (ln J)^2";
    static constexpr bool kStressFreeAtRest = true;
    double k = 0;  ///< bulk modulus (Pa)
    template <class T>
    FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const {
        const T k = T(this->k);
        const T lnJ = fastLog(J), iJ = T(1) / J;
        W = T(0.5) * k * lnJ * lnJ;
        dW = k * lnJ * iJ;
        d2W = k * (T(1) - lnJ) * iJ * iJ;
    }
};

/// U = -mu ln J + lambda/2 (ln J)^2, the volumetric part of HEML eq. (26), derivatives eq. (27).
/// Not stress-free at rest by itself (dU/dJ = -mu at J = 1): it balances the rest stress 2 C1 I of
/// C1 (I1 - 3) when C1 = mu/2.
struct HemlLogVolume {
    static constexpr const char* kEnergy = "-mu ln J + lambda/2 (ln J)^2";
    static constexpr bool kStressFreeAtRest = false;
    double mu = 0, lambda = 0;  ///< Pa
    template <class T>
    FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const {
        const T mu = T(this->mu), lambda = T(this->lambda);
        const T lnJ = fastLog(J), iJ = T(1) / J;
        W = -mu * lnJ + T(0.5) * lambda * lnJ * lnJ;
        dW = (lambda * lnJ - mu) * iJ;  // HEML eq. (27)
        d2W = (lambda - lambda * lnJ + mu) * iJ * iJ;
    }
};

} // namespace fascia::materials
