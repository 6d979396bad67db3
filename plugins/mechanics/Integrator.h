#pragma once
#include "fascia/base/StateIO.h"
#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"
#include "fascia/sim/StepTerms.h"
#include "fascia/sim/ThreadedStep.h"

#include <string>

namespace fascia::mechanics {

/// Shared parameters of the explicit integrators: mass-proportional (Rayleigh) damping,
/// m x'' + alpha m x' + f_int = f_ext.
class DampedIntegrator : public core::BaseIntegrator {
public:
    core::Param<double> m_damping{this, core::ParamSpec("damping").unit("1/s").min(0).help("mass-proportional Rayleigh damping alpha: damping force -alpha m v"), 0.0};
};

/// The state a checkpoint record names by path (integrators keep their history per state); an error of
/// the reader when the scene has no such state.
inline core::BaseMechanicalState& savedState(const core::Component& owner, core::StateReader& in, const std::string& path) {
    auto* s = dynamic_cast<core::BaseMechanicalState*>(owner.node()->root()->resolveComponent(path));
    if (!s) in.fail("[" + owner.path() + "] the checkpoint has a history for the state '" + path + "', which this scene does not have");
    return *s;
}

/// Runs update(x, v, f, 1/m) on every component of the nodes [lo, hi) of the group's state (x and v by
/// reference), on the flat arrays so that the compiler vectorises it.
template <class Update>
inline void updateRange(core::MechanicalGroup& g, long lo, long hi, Update&& update) {
    const double* __restrict invMass = g.invMass.data();
    double* __restrict xp = core::flat(g.state->x());
    double* __restrict vp = core::flat(g.state->v());
    const double* __restrict fp = core::flat(g.state->f());
    for (long i = lo; i < hi; ++i) {
        const double m = invMass[i];
        for (long c = 3 * i; c < 3 * i + 3; ++c) update(xp[c], vp[c], fp[c], m);
    }
}

/// The forces at time t, then update(x, v, f, 1/m) on every component of every node: in one parallel
/// region with the forces when the group's force fields allow it (core::stepThreaded), else
/// computeForces and then the update by chunks (core::forEachNodeRange). The same bits either way.
template <class Update>
inline void forcesThenUpdate(core::MechanicalGroup& g, double t, Update&& update) {
    if (core::stepThreaded(g, t, [&](long lo, long hi) { updateRange(g, lo, hi, update); })) return;
    g.computeForces(t);
    core::forEachNodeRange(static_cast<long>(g.state->x().size()), [&](long lo, long hi) { updateRange(g, lo, hi, update); });
}

} // namespace fascia::mechanics
