#pragma once
/// TestNaN: a constant force on every node that turns NaN on one node at a chosen step.
#include "fascia/base/StateIO.h"
#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"

#include <limits>

namespace fascia::test {

class TestNaN : public core::BaseForceField {
public:
    core::Param<Vec3> m_force{this, core::ParamSpec("force").unit("N").help("force on every node"), Vec3::Zero()};
    core::Param<int> m_nanAtStep{this, core::ParamSpec("nanAtStep").min(0).help("step (1-based) whose force is NaN; 0: never"), 0};
    core::Param<int> m_nanNode{this, core::ParamSpec("nanNode").min(0).help("node that gets the NaN"), 0};
    core::Param<double> m_criticalDt{this, core::ParamSpec("criticalDt").unit("s").above(0).help("stable time step it reports (default none)"),
                                     std::numeric_limits<double>::infinity()};

    void beginStep(double, double) override { ++m_step; }
    void addForce(core::BaseMechanicalState& state, Positions& f, double t) override {
        for (auto& fi : f) fi += m_force.get();
        if (m_step == m_nanAtStep.get() && m_nanNode.get() < int(f.size()))
            f[size_t(m_nanNode.get())][0] = std::numeric_limits<double>::quiet_NaN();
    }
    double stableTimeStep(const core::BaseMechanicalState&) const override { return m_criticalDt.get(); }
    void saveState(core::StateWriter& out) const override { out.put("step", long(m_step)); }
    void restoreState(core::StateReader& in) override { m_step = int(in.getLong("step")); }

private:
    int m_step = 0;
};

} // namespace fascia::test
