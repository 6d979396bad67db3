#pragma once
/// When a force field's Prony history advances, and over what time: one rule for HEMLForceField and
/// TLEDForceField.
///
/// A force field keeps two histories per Prony term: the previous one (committed) and the current
/// one, computed by the last force evaluation from the previous (TLED eq. (30), HEML eq. (20)). The
/// history advances when forces are asked for at a new time: the current history becomes the
/// previous one, and the new one is computed over the time elapsed since the last evaluation, with
/// the backward-Euler coefficients of that interval. Forces asked for again at the same time (the
/// iterations of a DynamicRelaxation load step, a Monitor's residual) recompute the current history
/// from the same previous one with the same coefficients. So an explicit integrator (forces at the
/// start of each step) and a static solver (forces at the end of each load step) both advance it
/// once per step, by the length of the step, a shortened last step included, and an extra
/// evaluation changes nothing.
///
/// A stress output at time t (cellData, for the state an observer writes) is the stress of that
/// state: at the time of the last evaluation (a static solver's load step), from the previous
/// history with the coefficients that evaluation used; at a later time (after an explicit step), from
/// the current history over the time since (what the next evaluation at that time computes).
#include "fascia/base/StateIO.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include <cmath>
#include <vector>

namespace fascia::viscoelastic {

class HistoryClock {
public:
    /// Two times closer than this fraction of the time step are one time (the round-off of the
    /// simulation's t0 + n dt against a solver's t + dt).
    static constexpr double kTolerance = 1e-9;

    /// Before a force evaluation at time t (s); dt is the scene's time step (s). True when the caller
    /// must first commit its history (the current states become the previous ones).
    bool beginEvaluation(double t, double dt) {
        if (m_evaluated && sameTime(t, dt)) return false;
        const bool commit = m_evaluated;
        m_elapsed = m_evaluated ? t - m_time : 0.0;
        m_evaluated = true;
        m_time = t;
        return commit;
    }
    /// True once a force evaluation has computed a current history.
    bool evaluated() const { return m_evaluated; }
    /// The time (s) the last evaluation advanced the history over; 0 for the first evaluation (the
    /// coefficients of the scene's time step then apply, see stepCoefficients).
    double elapsed() const { return m_elapsed; }

    /// What a stress output at time t reads.
    struct Output {
        bool current = false;  ///< the current history (else the previous one)
        bool lastCoefficients = true;  ///< with the coefficients of the last evaluation (else those of `elapsed`)
        double elapsed = 0;    ///< the history step (s) when not lastCoefficients
    };
    Output outputAt(double t, double dt) const {
        if (!m_evaluated || sameTime(t, dt)) return {};
        return {true, false, t - m_time};
    }

    /// The clock's state in a checkpoint (Simulation::save): with it, a restart advances the history
    /// exactly as the run it continues.
    void save(core::StateWriter& out) const {
        out.put("clockEvaluated", m_evaluated);
        out.put("clockTime", m_time);
        out.put("clockElapsed", m_elapsed);
    }
    void restore(core::StateReader& in) {
        m_evaluated = in.getBool("clockEvaluated");
        m_time = in.getDouble("clockTime");
        m_elapsed = in.getDouble("clockElapsed");
    }

private:
    bool sameTime(double t, double dt) const { return std::abs(t - m_time) <= kTolerance * dt; }
    bool m_evaluated = false;
    double m_time = 0, m_elapsed = 0;
};

/// A_i and B_i of the series p (TLED eq. (30)) for a history step of `elapsed` s, dt the scene's time
/// step (s): those of dt when elapsed is not positive (the first evaluation, or time set back) or is
/// dt within HistoryClock::kTolerance, so that whole steps give the same coefficients every time.
inline void stepCoefficients(const ViscoelasticProny& p, double elapsed, double dt, std::vector<double>& A,
                             std::vector<double>& B) {
    const bool whole = !(elapsed > 0) || std::abs(elapsed - dt) <= HistoryClock::kTolerance * dt;
    p.coefficients(whole ? dt : elapsed, A, B);
}

} // namespace fascia::viscoelastic
