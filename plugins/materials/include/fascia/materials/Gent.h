#pragma once
/// Gent's limiting-chain-extensibility law (Gent 1996, Rubber Chem. Technol. 69), as FEBio's
/// uncoupled Gent: the isochoric part (inlined by the force fields, see ComposedLaw.h), composed
/// with U(J) = k/2 (ln J)^2, and its component. The worked example of docs/design.md, section 4.1.
#include "fascia/materials/Laws.h"

#include <algorithm>

namespace fascia::materials {

/// ln(1 - x) for x < 1, accurate where x is small (the rest state, where the energy is
/// mu/2 (I1bar - 3) to first order): fastLog(1 - x) alone would lose the digits of x that the
/// rounding of 1 - x drops. With u = 1 - x rounded, ln(1 - x) = ln(u) (-x)/(u - 1) to a few ulp
/// (the log1p construction), and -x where u rounds to 1. Branch-free (two selects).
template <class T>
FASCIA_HD inline T lnOneMinus(T x) {
    const T u = T(1) - x, du = u - T(1);
    const T safe = du == T(0) ? T(-1) : du;
    const T r = fastLog(u) * (-x / safe);
    return du == T(0) ? -x : r;
}

/// The isochoric part of Gent's law: W = -mu Jm/2 ln(1 - (I1bar - 3)/Jm), I1bar = J^(-2/3) I1.
/// Jm is the limit of I1bar - 3: the energy and the stress grow without bound as the chains reach
/// it, and beyond it W is not defined. Kept finite (docs/design.md, section 4.1): with
/// x = (I1bar - 3)/Jm, the law is Gent's up to x = kLock, and beyond it continues along its
/// second-order Taylor polynomial in x at kLock (the J0 treatment of evaluateLaw, in I1bar), so W
/// is C^2, convex in x, and finite for every deformation: an element driven past the lock pushes
/// back with a stiffness 1/(1 - kLock)^2 = 10^4 times the initial one, never a NaN.
/// Derivatives: with xc = min(x, kLock), d = max(x - kLock, 0),
///   W = mu Jm/2 [-ln(1 - xc) + d/(1 - xc) + d^2/(2 (1 - xc)^2)],
///   w = dW/dI1bar = mu/2 [1/(1 - xc) + d/(1 - xc)^2],  dI1 = J^(-2/3) w,  dJiso = -2/(3 J) w I1bar.
/// Stress-free at rest; small-strain shear modulus mu; Jm -> infinity gives mu/2 (I1bar - 3).
struct GentIso {
    static constexpr unsigned uses = 0;
    static constexpr const char* kEnergy = "-mu Jm/2 ln(1 - (I1bar - 3)/Jm)";
    static constexpr bool kStressFreeAtRest = true;
    static constexpr double kLock = 0.99;  ///< the fraction of Jm beyond which W is its Taylor polynomial
    double mu = 0;  ///< small-strain shear modulus (Pa)
    double Jm = 0;  ///< the limit of I1bar - 3 (> 0)
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T a = T(0.5 * mu * Jm), iJm = T(1.0 / Jm), lock = T(kLock);
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T I1b = in.I1 * t2, x = (I1b - T(3)) * iJm;
        const T xc = std::min(x, lock), d = std::max(x - lock, T(0));
        const T g = T(1) / (T(1) - xc);  // 1/(1 - xc), at most 1/(1 - kLock)
        r.W += a * (-lnOneMinus(xc) + d * g * (T(1) + T(0.5) * d * g));
        const T w = a * iJm * g * (T(1) + d * g);
        r.dI1 += w * t2;
        r.dJiso += -T(2.0 / 3.0) * w * I1b * iJ;
    }
};
using GentLaw = ComposedLaw<GentIso, LogVolume>;

/// The Gent material (see GentIso). Parameters: mu (FEBio's G), Jm and k (FEBio's names). The
/// stable time step (from waveSpeed) is a rest value: the law stiffens as I1bar - 3 nears Jm.
class Gent : public Material<GentLaw> {
public:
    static constexpr const char* kName = "Gent";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "mu=1000;Jm=2;k=20000";
    static constexpr const char* kTitle = "Gent, limiting chain extensibility (Gent 1996; FEBio's uncoupled Gent)";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "I1bar = J^(-2/3) tr C, C = F^T F, J = det F; mu = FEBio's G; beyond I1bar - 3 = 0.99 Jm its second-order Taylor polynomial in I1bar (finite at and past the lock); shear modulus mu, bulk modulus k";
    void init() override {
        m_law.mu = m_mu.get();
        m_law.Jm = m_Jm.get();
        m_law.k = m_k.get();
    }
    double shearModulus() const override { return m_law.mu; }
    double bulkModulus() const override { return m_law.k; }

    core::Param<double> m_mu{this, core::ParamSpec("mu").unit("Pa").above(0).required().help("small-strain shear modulus mu of -mu Jm/2 ln(1 - (I1bar - 3)/Jm) (FEBio's G)")};
    core::Param<double> m_Jm{this, core::ParamSpec("Jm").above(0).required().help("the limit Jm of I1bar - 3, where the chains lock (large values approach the neo-Hookean mu/2 (I1bar - 3))")};
    core::Param<double> m_k{this, core::ParamSpec("k").unit("Pa").above(0).required().help("bulk modulus k of k/2 (ln J)^2 (FEBio's k)")};
};

} // namespace fascia::materials
