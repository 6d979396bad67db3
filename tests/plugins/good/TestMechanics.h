#pragma once
/// A minimal state, mass and integrator, so the core loop can be tested without the mechanics plugin.
#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"

namespace fascia::test {

class TestState : public core::BaseMechanicalState {
public:
    core::Param<Positions> m_position{this, core::ParamSpec("position").unit("m").help("rest positions, 3 numbers per node"),
                                      Positions{Vec3::Zero()}};
    void init() override {
        m_x0 = m_position.get();
        resize(m_x0.size());
    }
};

class TestMass : public core::BaseMass {
public:
    core::Param<double> m_mass{this, core::ParamSpec("mass").unit("kg").above(0).help("mass of each node"), 1.0};
    std::vector<core::Component*> dependencies() const override {
        if (auto* s = node()->findInContext<core::BaseMechanicalState>()) return {s};
        return {};
    }
    void init() override {
        auto* s = node()->findInContext<core::BaseMechanicalState>();
        if (!s) fail("no state in its context");
        m_masses.assign(s->size(), m_mass.get());
    }
};

/// v += dt f / m, x += dt v.
class TestEuler : public core::BaseIntegrator {
public:
    void step(core::MechanicalGroup& g, double t, double dt) override {
        g.computeForces(t);
        auto& x = g.state->x();
        auto& v = g.state->v();
        const auto& f = g.state->f();
        for (size_t i = 0; i < x.size(); ++i) {
            v[i] += dt * g.invMass[i] * f[i];
            x[i] += dt * v[i];
        }
        g.projectState(t + dt);
    }
};

} // namespace fascia::test
