#include "fascia/viscoelastic/ViscoelasticProny.h"
#include "fascia/viscoelastic/ElementHistory.h"

#include "fascia/base/Error.h"
#include "fascia/base/Format.h"

#include <cmath>

namespace fascia::viscoelastic {

using core::formatNumber;

ElementHistory::~ElementHistory() = default;  // (its key function: one type_info for every plugin)

void ViscoelasticProny::init() {
    const NumberList& a = m_alpha.get();
    const NumberList& t = m_tau.get();
    if (a.empty()) fail(m_alpha, "alpha is empty: give at least one Prony term, e.g. alpha=\"0.5\" tau=\"0.58\"");
    if (t.size() != a.size())
        fail(m_tau, "tau has " + std::to_string(t.size()) + " entries but alpha has " + std::to_string(a.size()) +
                        ": give one time constant per Prony term");
    // ranges of single entries are checked at parse time; repeat them here for values set from code
    for (size_t i = 0; i < a.size(); ++i) {
        if (!(a[i] > 0) || !std::isfinite(a[i]))
            fail(m_alpha, "alpha entry " + std::to_string(i) + " (" + formatNumber(a[i], 10) + ") must be > 0");
        if (!(t[i] > 0) || !std::isfinite(t[i]))
            fail(m_tau, "tau entry " + std::to_string(i) + " (" + formatNumber(t[i], 10) + " s) must be > 0");
    }
    double sum = 0;
    for (double v : a) sum += v;
    if (!(sum < 1))
        fail(m_alpha, "the alpha entries sum to " + formatNumber(sum, 10) +
                          ", which leaves no long-term stiffness (alpha_inf = 1 - sum must be > 0, TLED eq. (6))",
             {"reduce the alpha_i so that their sum is below 1"});
    if (m_dt > 0) coefficients(m_dt, m_A, m_B);
}

void ViscoelasticProny::dtChanged(double dt) {
    if (!(dt > 0) || !std::isfinite(dt))
        core::throwInputError(loc(), "ViscoelasticProny '" + name() + "': time step " + formatNumber(dt, 10) + " s is not positive");
    m_dt = dt;
    coefficients(dt, m_A, m_B);
}

double ViscoelasticProny::alphaInfinity() const {
    double s = 1.0;
    for (double v : m_alpha.get()) s -= v;
    return s;
}

double ViscoelasticProny::relaxation(double t) const {
    // TLED eq. (7)
    double r = 1.0;
    const NumberList& a = m_alpha.get();
    const NumberList& tau = m_tau.get();
    for (size_t i = 0; i < a.size() && i < tau.size(); ++i) r -= a[i] * (1.0 - std::exp(-t / tau[i]));
    return r;
}

ViscoelasticProny::Apply ViscoelasticProny::apply() const {
    const std::string& s = m_apply.get();
    if (s == "volumetric") return Apply::Volumetric;
    if (s == "both") return Apply::Both;
    return Apply::Isochoric;
}

void ViscoelasticProny::coefficients(double dt, std::vector<double>& A, std::vector<double>& B) const {
    coefficients(m_alpha.get(), m_tau.get(), dt, A, B);
}

void ViscoelasticProny::coefficients(const NumberList& alpha, const NumberList& tau, double dt,
                                     std::vector<double>& A, std::vector<double>& B) {
    if (alpha.size() != tau.size())
        core::throwInputError({}, "Prony series: " + std::to_string(alpha.size()) + " alpha entries but " +
                                      std::to_string(tau.size()) + " tau entries");
    const size_t n = alpha.size();
    A.resize(n);
    B.resize(n);
    for (size_t i = 0; i < n; ++i) {
        // TLED eq. (30), HEML eq. (20)
        A[i] = dt * alpha[i] / (dt + tau[i]);
        B[i] = tau[i] / (dt + tau[i]);
    }
}

void ViscoelasticProny::update(const double* R, double* Y, size_t n, size_t stride, double* out) const {
    const size_t terms = m_A.size();
    if (terms != termCount() || !hasCoefficients())
        core::throwSimulationError(path() + ": Prony update called before a time step was set (dtChanged)");
    for (size_t k = 0; k < n; ++k) {
        const double r = R[k];
        double s = r;
        for (size_t i = 0; i < terms; ++i) {
            double& y = Y[i * stride + k];
            y = m_A[i] * r + m_B[i] * y;  // TLED eq. (30)
            s -= y;                       // TLED eq. (24)
        }
        out[k] = s;
    }
}

} // namespace fascia::viscoelastic
