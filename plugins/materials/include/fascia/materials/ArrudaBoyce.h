#pragma once
/// Arruda-Boyce (eight-chain) rubber-elastic law, as in NiftySim: the law struct (inlined by the
/// force fields, see Material.h) and its component.
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// The isochoric part of the Arruda & Boyce (1993, J. Mech. Phys. Solids 41) eight-chain model, by
/// the five-term series of the inverse Langevin function (the form NiftySim uses, Johnsen et al.
/// 2015, Int. J. CARS 10), with C_i = 1/2, 1/20, 11/1050, 19/7000, 519/673750 and I1bar =
/// J^(-2/3) I1; lambdaM the locking stretch (> 1; the truncated series stiffens as the chains near
/// it but does not lock). With the volumetric part kappa/2 (J - 1)^2, as NeoHookeanLaw:
/// lambdaM -> infinity gives the neo-Hookean mu/2 (I1bar - 3) + kappa/2 (J - 1)^2.
/// I1bar^i - 3^i is evaluated as S_i = I1bar S_{i-1} + 3^(i-1) (I1bar - 3), S_1 = I1bar - 3, which
/// keeps W accurate near rest (no cancellation of large terms). With w = dW/dI1bar =
/// mu sum_i i C_i I1bar^(i-1) / lambdaM^(2i-2):  dI1 = J^(-2/3) w,  dJiso = -2/(3 J) w I1bar.
/// Stress-free at rest. Small-strain shear modulus 2 w(3) = mu (1 + 3/(5 lm^2) + 99/(175 lm^4) +
/// 513/(875 lm^6) + 42039/(67375 lm^8)) (initialShearModulus), not mu. No libm: invCbrt only.
struct ArrudaBoyceIso {
    static constexpr unsigned uses = 0;
    static constexpr const char* kEnergy = "mu sum_{i=1}^{5} C_i/lambdaM^(2i-2) (I1bar^i - 3^i)";
    static constexpr bool kStressFreeAtRest = true;
    double mu = 0;       ///< Pa (the shear modulus only in the limit lambdaM -> infinity)
    double lambdaM = 0;  ///< locking stretch, > 1
    /// The coefficients mu C_i / lambdaM^(2i-2) of W, i = 1..5 (computed in double, then rounded to T).
    template <class T>
    FASCIA_HD void coefficients(T a[5]) const {
        const double b = 1.0 / (lambdaM * lambdaM);
        a[0] = T(mu * 0.5);
        a[1] = T(mu * (1.0 / 20.0) * b);
        a[2] = T(mu * (11.0 / 1050.0) * b * b);
        a[3] = T(mu * (19.0 / 7000.0) * b * b * b);
        a[4] = T(mu * (519.0 / 673750.0) * b * b * b * b);
    }
    /// dW/dI1bar at I1bar = x.
    template <class T>
    FASCIA_HD T dWdI1bar(T x) const {
        T a[5];
        coefficients(a);
        return a[0] + x * (T(2) * a[1] + x * (T(3) * a[2] + x * (T(4) * a[3] + x * T(5) * a[4])));
    }
    /// Small-strain shear modulus 2 dW/dI1bar at I1bar = 3.
    double initialShearModulus() const { return 2.0 * dWdI1bar(3.0); }
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T x = in.I1 * t2, d = x - T(3);
        const T S2 = x * d + T(3) * d, S3 = x * S2 + T(9) * d, S4 = x * S3 + T(27) * d, S5 = x * S4 + T(81) * d;
        T a[5];
        coefficients(a);
        r.W += a[0] * d + a[1] * S2 + a[2] * S3 + a[3] * S4 + a[4] * S5;
        const T w = dWdI1bar(x);
        r.dI1 += w * t2;
        r.dJiso += -T(2.0 / 3.0) * w * x * iJ;
    }
};
using ArrudaBoyceLaw = ComposedLaw<ArrudaBoyceIso, QuadraticVolume>;

/// The Arruda-Boyce material (see ArrudaBoyceLaw for W and its derivatives). Parameters: mu,
/// lambdaM (the locking stretch, > 1) and kappa (bulk modulus). shearModulus() is the small-strain
/// shear modulus of the series, mu (1 + 3/(5 lambdaM^2) + ...), which the stable time step uses.
/// Stress-free at rest.
class ArrudaBoyce : public Material<ArrudaBoyceLaw> {
public:
    static constexpr const char* kName = "ArrudaBoyce";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "mu=1000;lambdaM=2;kappa=20000";
    static constexpr const char* kTitle = "Arruda-Boyce eight-chain (Arruda and Boyce 1993, five-term series as NiftySim)";
    static constexpr const char* kTerms =
        "C_i = 1/2, 1/20, 11/1050, 19/7000, 519/673750, I1bar = J^(-2/3) tr C, J = det F; small-strain shear modulus mu (1 + 3/(5 lambdaM^2) + 99/(175 lambdaM^4) + 513/(875 lambdaM^6) + 42039/(67375 lambdaM^8))";
    void init() override {
        m_law.mu = m_mu.get();
        m_law.lambdaM = m_lambdaM.get();
        m_law.kappa = m_kappa.get();
    }
    double shearModulus() const override { return m_law.initialShearModulus(); }
    double bulkModulus() const override { return m_law.kappa; }

    core::Param<double> m_mu{this, core::ParamSpec("mu").unit("Pa").above(0).required().help("modulus mu of mu sum_i C_i/lambdaM^(2i-2) (I1bar^i - 3^i); the small-strain shear modulus is mu (1 + 3/(5 lambdaM^2) + 99/(175 lambdaM^4) + ...)")};
    core::Param<double> m_lambdaM{this, core::ParamSpec("lambdaM").above(1).required().help("locking stretch lambdaM of the chains (> 1; large values approach the neo-Hookean mu/2 (I1bar - 3))")};
    core::Param<double> m_kappa{this, core::ParamSpec("kappa").unit("Pa").above(0).required().help("bulk modulus kappa of kappa/2 (J - 1)^2")};
};

} // namespace fascia::materials
