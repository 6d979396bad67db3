#pragma once
/// The isochoric parts of the built-in laws and the laws composed of them (ComposedLaw.h: an
/// isochoric part plus a volumetric part of Volumetric.h). Force fields dispatch once per element
/// loop on Material<Law> and inline these; user laws follow the same shape.
///
/// Every part is templated on the scalar type T (Material.h): its parameters are double members,
/// converted to T once per call; its constants are written T(...), so that the double instance is
/// exactly the double code and the float instance computes in float throughout.
/// Every derivative is a partial derivative of W(I1, I2, J, I4, I6) w.r.t. the plain invariants
/// (Material.h, Response). No law calls pow: J^(-1/3) comes from invCbrt() (exponent bits plus a
/// division-free Newton refinement, FastMath.h), 1/J from (J^(-1/3))^3. Only the logarithmic
/// volumetric parts (HEML eq. (26), FEBio's k/2 (ln J)^2) need a logarithm: fastLog(), likewise
/// without libm. Everything is FASCIA_HD. Each part's W is its kEnergy text, written once.
#include "fascia/base/Hd.h"
#include "fascia/materials/ComposedLaw.h"
#include "fascia/materials/FastMath.h"
#include "fascia/materials/Material.h"

#include <cmath>

namespace fascia::materials {

/// Saint Venant-Kirchhoff (HEML Table 3), with E = (C - I)/2 written with the invariants:
/// tr E = (I1 - 3)/2, tr(E^2) = (I1^2 - 2 I2 - 2 I1 + 3)/4, so W = lambda/8 (I1 - 3)^2 +
/// mu/4 (I1^2 - 2 I2 - 2 I1 + 3). All of W is this part: no volumetric part (the HEML J0 treatment
/// does nothing for it, and, HEML section 4.2, it softens under strong compression).
struct StVenantKirchhoffIso {
    static constexpr unsigned uses = BaseMaterial::UsesI2;
    static constexpr const char* kEnergy = "lambda/2 (tr E)^2 + mu tr(E^2)";
    static constexpr bool kStressFreeAtRest = true;
    double lambda = 0, mu = 0;  ///< Lame coefficients (Pa)
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T lambda = T(this->lambda), mu = T(this->mu);
        const T a = in.I1 - T(3);
        r.W += T(0.125) * lambda * a * a + T(0.25) * mu * (in.I1 * in.I1 - T(2) * in.I2 - T(2) * in.I1 + T(3));
        r.dI1 += T(0.25) * lambda * a + T(0.5) * mu * (in.I1 - T(1));
        r.dI2 += -T(0.5) * mu;
    }
};
using StVenantKirchhoffLaw = ComposedLaw<StVenantKirchhoffIso, NoVolume>;

/// C1 (I1 - 3) in the plain I1 (HEML Table 3 and eq. (26)): its rest stress is S = 2 C1 I.
struct LinearI1Iso {
    static constexpr unsigned uses = 0;
    static constexpr const char* kEnergy = "C1 (I1 - 3)";
    static constexpr bool kStressFreeAtRest = false;
    double C1 = 0;  ///< Pa
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T C1 = T(this->C1);
        r.W += C1 * (in.I1 - T(3));
        r.dI1 += C1;
    }
};

/// C1 (I1 - 3) + C2 (I2 - 3) in the plain invariants (HEML Table 3): rest stress S = 2 (C1 + 2 C2) I.
struct LinearI1I2Iso {
    static constexpr unsigned uses = BaseMaterial::UsesI2;
    static constexpr const char* kEnergy = "C1 (I1 - 3) + C2 (I2 - 3)";
    static constexpr bool kStressFreeAtRest = false;
    double C1 = 0, C2 = 0;  ///< Pa
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T C1 = T(this->C1), C2 = T(this->C2);
        r.W += C1 * (in.I1 - T(3)) + C2 * (in.I2 - T(3));
        r.dI1 += C1;
        r.dI2 += C2;
    }
};

/// The HEML paper's "incompressible" neo-Hookean (Table 3): C1 (I1 - 3) and no volumetric part.
/// Nothing resists volume change except through I1, and the rest state is NOT stress-free
/// (S = 2 C1 I at C = I). "Incompressible" only in the paper's sense (the law one would use with an
/// incompressibility constraint, which HEML does not impose).
using IncompressibleNeoHookeanLaw = ComposedLaw<LinearI1Iso, NoVolume>;

/// The HEML paper's "incompressible" Mooney-Rivlin (Table 3): no volumetric part; not stress-free
/// at rest (S = 2 (C1 + 2 C2) I at C = I).
using IncompressibleMooneyRivlinLaw = ComposedLaw<LinearI1I2Iso, NoVolume>;

/// Compressible neo-Hookean of HEML eq. (26): C1 (I1 - 3) with the volumetric part
/// -mu ln J + lambda/2 (ln J)^2, derivatives eq. (27). The two parts balance each other's rest
/// stress only when C1 = mu/2 (then it is the classical Simo-Pister / Bonet-Wood neo-Hookean with
/// Lame coefficients lambda, mu).
struct CompressibleNeoHookeanLaw : ComposedLaw<LinearI1Iso, HemlLogVolume> {
    bool stressFreeAtRest() const { return C1 == 0.5 * mu; }
};

/// C1 (I1bar - 3) + C2 (I2bar - 3), I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2 (the isochoric split
/// of HEML eq. (21)-(25)): dI1 = C1 J^(-2/3), dI2 = C2 J^(-4/3),
/// dJiso = -2/(3 J) (C1 I1bar + 2 C2 I2bar). Stress-free at rest; shear modulus 2 (C1 + C2).
struct MooneyRivlinIso {
    static constexpr unsigned uses = BaseMaterial::UsesI2;
    static constexpr const char* kEnergy = "C1 (I1bar - 3) + C2 (I2bar - 3)";
    static constexpr bool kStressFreeAtRest = true;
    double C1 = 0, C2 = 0;  ///< Pa
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T C1 = T(this->C1), C2 = T(this->C2);
        const T t = invCbrt(in.J), t2 = t * t, t4 = t2 * t2, iJ = t2 * t;
        const T I1b = in.I1 * t2, I2b = in.I2 * t4;
        r.W += C1 * (I1b - T(3)) + C2 * (I2b - T(3));
        r.dI1 += C1 * t2;
        r.dI2 += C2 * t4;
        r.dJiso += -T(2.0 / 3.0) * (C1 * I1b + T(2) * C2 * I2b) * iJ;
    }
};
/// Compressible Mooney-Rivlin (HEML eq. (21)-(25)): bulk modulus kappa.
using CompressibleMooneyRivlinLaw = ComposedLaw<MooneyRivlinIso, QuadraticVolume>;
/// FEBio's uncoupled Mooney-Rivlin: the same isochoric part with FEBio's U(J) = k/2 (ln J)^2.
using UncoupledMooneyRivlinLaw = ComposedLaw<MooneyRivlinIso, LogVolume>;

/// mu/2 (I1bar - 3) (TLED eq. (9), (31)-(32) without the fibre term): dI1 = mu/2 J^(-2/3),
/// dJiso = -mu/(3 J) I1bar. Stress-free at rest; shear modulus mu.
struct NeoHookeanIso {
    static constexpr unsigned uses = 0;
    static constexpr const char* kEnergy = "mu/2 (I1bar - 3)";
    static constexpr bool kStressFreeAtRest = true;
    double mu = 0;  ///< Pa
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T mu = T(this->mu);
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T I1b = in.I1 * t2;
        r.W += T(0.5) * mu * (I1b - T(3));
        r.dI1 += T(0.5) * mu * t2;
        r.dJiso += -T(1.0 / 3.0) * mu * I1b * iJ;
    }
};
/// Neo-Hookean with the isochoric split, as in TLED eq. (9), (31)-(32) without the fibre term.
using NeoHookeanLaw = ComposedLaw<NeoHookeanIso, QuadraticVolume>;

/// The isochoric part of the transversely isotropic neo-Hookean of the TLED paper (section 3.2.2,
/// eq. (31)-(33)), I4bar = J^(-2/3) a0.C a0. The fibre term is eta/4, not the eta/2 printed in TLED
/// eq. (31): eq. (33) and Appendix A (and the published implementations) use the stress
/// eta J^(-2/3) (I4bar - 1)(A0 - I4/3 C^-1), which is the derivative 2 dW/dC of eta/4 (I4bar - 1)^2.
struct TransverselyIsotropicIso {
    static constexpr unsigned uses = BaseMaterial::UsesI4;
    static constexpr const char* kEnergy = "mu/2 (I1bar - 3) + eta/4 (I4bar - 1)^2";
    static constexpr bool kStressFreeAtRest = true;
    double mu = 0, eta = 0;  ///< Pa
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T mu = T(this->mu), eta = T(this->eta);
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T I1b = in.I1 * t2, I4b = in.I4 * t2, e4 = I4b - T(1);
        r.W += T(0.5) * mu * (I1b - T(3)) + T(0.25) * eta * e4 * e4;
        r.dI1 += T(0.5) * mu * t2;
        r.dI4 += T(0.5) * eta * e4 * t2;
        r.dJiso += -T(1.0 / 3.0) * (mu * I1b + eta * e4 * I4b) * iJ;
    }
};
using TransverselyIsotropicLaw = ComposedLaw<TransverselyIsotropicIso, QuadraticVolume>;

/// The orthotropic extension (TLED section 3.2.3): the transversely isotropic part plus a second
/// fibre family b0 in the same eq. (33) convention, I6bar = J^(-2/3) b0.C b0.
struct OrthotropicIso {
    static constexpr unsigned uses = BaseMaterial::UsesI4 | BaseMaterial::UsesI6;
    static constexpr const char* kEnergy = "mu/2 (I1bar - 3) + eta/4 (I4bar - 1)^2 + eta2/4 (I6bar - 1)^2";
    static constexpr bool kStressFreeAtRest = true;
    double mu = 0, eta = 0, eta2 = 0;  ///< Pa
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T mu = T(this->mu), eta = T(this->eta), eta2 = T(this->eta2);
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T I1b = in.I1 * t2, I4b = in.I4 * t2, I6b = in.I6 * t2;
        const T e4 = I4b - T(1), e6 = I6b - T(1);
        r.W += T(0.5) * mu * (I1b - T(3)) + T(0.25) * eta * e4 * e4 + T(0.25) * eta2 * e6 * e6;
        r.dI1 += T(0.5) * mu * t2;
        r.dI4 += T(0.5) * eta * e4 * t2;
        r.dI6 += T(0.5) * eta2 * e6 * t2;
        r.dJiso += -T(1.0 / 3.0) * (mu * I1b + eta * e4 * I4b + eta2 * e6 * I6b) * iJ;
    }
};
using OrthotropicLaw = ComposedLaw<OrthotropicIso, QuadraticVolume>;

/// Lame and bulk moduli from Young's modulus E (Pa) and Poisson's ratio nu.
FASCIA_HD inline double lameMu(double E, double nu) { return E / (2.0 * (1.0 + nu)); }
FASCIA_HD inline double lameLambda(double E, double nu) { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
FASCIA_HD inline double bulkFromE(double E, double nu) { return E / (3.0 * (1.0 - 2.0 * nu)); }

} // namespace fascia::materials
