#pragma once
/// Prony-series viscoelasticity shared by TLEDForceField and HEMLForceField.
///
/// Relaxation function (TLED eq. (5)-(7), HEML eq. (15)-(16)), normalised so that alpha(0) = 1:
///   alpha(t) = 1 - sum_i alpha_i (1 - exp(-t / tau_i)),   alpha_inf = 1 - sum_i alpha_i > 0.
/// A visco-hyperelastic response R (a stress for TLED, a nodal force for HEML) is
///   R_visco(t) = int_0^t alpha(t - s) dR/ds ds = R(t) - sum_i Y_i(t)           TLED eq. (22), HEML eq. (18)
/// with one state variable Y_i per Prony term obeying dY_i/dt = (alpha_i R - Y_i) / tau_i (TLED eq. (29)).
/// Backward Euler gives the recurrence used by both papers,
///   Y_i^n = A_i R^n + B_i Y_i^(n-1),  A_i = dt alpha_i / (dt + tau_i),  B_i = tau_i / (dt + tau_i)
/// which is TLED eq. (30) and, with R the hyperelastic nodal force f, exactly HEML eq. (20)
/// (same A_i and B_i; HEML applies it to forces, TLED to the second Piola-Kirchhoff stress).
/// Note: TLED eq. (21) and (23) print the kernel as exp(-(s - t)/tau), a sign slip; the rate form
/// eq. (29), HEML eq. (18)-(19) and this code use the decaying kernel exp(-(t - s)/tau).
/// The update is first order in dt (relative error about dt / (2 tau)).
///
/// The component sits in the node of the force field it modifies; the force field finds it with
/// `node()->findLocal<fascia::viscoelastic::ViscoelasticProny>()` in its init() and keeps its
/// state variables itself (per element and term for TLED, per node and term for HEML).
///
/// XML: `<ViscoelasticProny alpha="0.5" tau="0.58" apply="isochoric"/>`
#include "fascia/base/Component.h"

#include <cstddef>
#include <vector>

namespace fascia::viscoelastic {

class ViscoelasticProny : public core::Component {
public:
    /// Which part of a split (isochoric + volumetric) hyperelastic response relaxes (TLED 3.3, 7).
    enum class Apply { Isochoric, Volumetric, Both };

    void init() override;
    /// Recomputes A_i and B_i for the new time step (TLED eq. (30)).
    void dtChanged(double dt) override;

    /// Number of Prony terms N (>= 1 after init).
    size_t termCount() const { return m_alpha.get().size(); }
    /// Relative moduli alpha_i (dimensionless, each > 0, sum < 1).
    const NumberList& alphas() const { return m_alpha.get(); }
    /// Time constants tau_i (s, each > 0).
    const NumberList& taus() const { return m_tau.get(); }
    double alpha(size_t i) const { return m_alpha.get()[i]; }
    double tau(size_t i) const { return m_tau.get()[i]; }
    /// Long-term relative modulus alpha_inf = 1 - sum_i alpha_i (TLED eq. (6)).
    double alphaInfinity() const;
    /// The relaxation function alpha(t) of TLED eq. (7) / HEML eq. (16) (dimensionless, t in s).
    double relaxation(double t) const;

    Apply apply() const;
    bool relaxesIsochoric() const { return apply() != Apply::Volumetric; }
    bool relaxesVolumetric() const { return apply() != Apply::Isochoric; }
    /// A located input error at the `apply` attribute, for the force fields' check that the parts
    /// they relax are stress-free at rest (fascia/materials/RelaxationSplit.h).
    [[noreturn]] void failApply(const std::string& message) const { fail(m_apply, message); }

    /// Time step (s) the current coefficients were computed for; 0 before the first dtChanged().
    double dt() const { return m_dt; }
    /// True once dtChanged() (or setTimeStep()) has given a time step.
    bool hasCoefficients() const { return m_dt > 0; }
    /// A_i = dt alpha_i / (dt + tau_i) for the current dt (TLED eq. (30), HEML eq. (20)).
    const std::vector<double>& A() const { return m_A; }
    /// B_i = tau_i / (dt + tau_i) for the current dt (TLED eq. (30), HEML eq. (20)).
    const std::vector<double>& B() const { return m_B; }

    /// Computes A_i and B_i for a given dt (s) without changing the component's own coefficients.
    void coefficients(double dt, std::vector<double>& A, std::vector<double>& B) const;
    /// Same, for any term lists (no component needed); alpha and tau must have the same length.
    static void coefficients(const NumberList& alpha, const NumberList& tau, double dt, std::vector<double>& A,
                             std::vector<double>& B);
    /// Sets dt from code (same as dtChanged), for embedding programs and tests.
    void setTimeStep(double dt) { dtChanged(dt); }

    /// One step of TLED eq. (30) / HEML eq. (20) on n-component arrays, for every term i:
    ///   Y[i][k] = A_i R[k] + B_i Y[i][k]   (Y laid out term-major: Y + i * stride), then
    ///   out[k] = R[k] - sum_i Y[i][k]      (TLED eq. (24), HEML eq. (18); out may alias R).
    /// A convenience for scalar code; force fields usually inline this.
    void update(const double* R, double* Y, size_t n, size_t stride, double* out) const;

private:
    core::Param<NumberList> m_alpha{this, core::ParamSpec("alpha").required().above(0).below(1).help(
        "relative moduli alpha_i of the Prony terms (TLED eq. (5)), each > 0, sum < 1 (alpha_inf = 1 - sum > 0)")};
    core::Param<NumberList> m_tau{this, core::ParamSpec("tau").unit("s").required().above(0).help(
        "time constants tau_i of the Prony terms (TLED eq. (5)), one per alpha, each > 0")};
    core::Param<std::string> m_apply{this, core::ParamSpec("apply").choices({"isochoric", "volumetric", "both"}).help(
        "which part of the hyperelastic response relaxes (TLED sections 3.3 and 7): the isochoric part, "
        "the volumetric (pure J) part, or both"), "isochoric"};

    double m_dt = 0.0;
    std::vector<double> m_A, m_B;
};

} // namespace fascia::viscoelastic
