#include "CudaStep.h"

#include "fascia/elements/Errors.h"

#include <algorithm>

namespace fascia::cuda {

void CudaStep::adopt(core::MechanicalGroup& g) {
    Body b;
    b.state = g.state;
    // every component is checked before the device: a scene the GPU cannot run says so anywhere
    b.setup = buildStepSetup(*this, g);
    const Precision p = m_precision.get() == "float" ? Precision::Float : Precision::Double;
    if (m_emulate.get()) {
        b.runner = makeEmulatedRunner(b.setup, p);
    } else {
        std::string why;
        if (cudaDevices(why) == 0)
            fail("no usable CUDA device (" + why + ")", {"run on a machine with an NVIDIA GPU and its driver, or remove CudaStep to run on the CPU"});
        b.runner = makeCudaRunner(b.setup, p, m_blockSize.get());
    }
    b.kick.halfStepStart = b.setup.halfStepStart;
    const size_t n = g.state->size();
    b.u.resize(3 * n);
    b.v.resize(3 * n);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            b.u[3 * i + static_cast<size_t>(c)] = g.state->x()[i][c] - g.state->x0()[i][c];
            b.v[3 * i + static_cast<size_t>(c)] = g.state->v()[i][c];
        }
    b.runner->setState(b.u, b.v);
    m_bodies.push_back(std::move(b));
}

void CudaStep::step(core::MechanicalGroup& g, double t, double dt) {
    auto it = std::find_if(m_bodies.begin(), m_bodies.end(), [&](const Body& b) { return b.state == g.state; });
    if (it == m_bodies.end()) elements::runtimeError(*this, "the state '" + g.state->path() + "' was not adopted at init");
    Body& b = *it;
    if (!b.setup.series.empty()) {
        // the device evaluates the forces once a step, at its start: the history advances every step,
        // with the coefficients TLEDForceField's beginForces takes (viscoelastic/HistoryClock.h)
        b.clock.beginEvaluation(t, dt);
        pronyCoefficients(b.setup, b.clock.elapsed(), dt, b.nextA, b.nextB);
        if (b.nextA != b.A || b.nextB != b.B) {
            b.A = b.nextA;
            b.B = b.nextB;
            b.runner->setRelaxation(b.A, b.B);
        }
    }
    b.runner->elementPass();
    NodeParams<double> p = nodeParams(g, b.setup, t, dt, b.kick.next(dt));
    b.central.next(dt, p);
    if (!b.setup.targetAt.empty()) {
        motionTargets(g, b.setup, t + dt, b.tu, b.tv);
        b.runner->setTargets(b.tu, b.tv);
    }
    b.runner->nodePass(p);
    b.runner->getState(b.u, b.v);
    Positions& x = g.state->x();
    Positions& v = g.state->v();
    const Positions& X = g.state->x0();
    for (size_t i = 0; i < x.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            x[i][c] = X[i][c] + b.u[3 * i + static_cast<size_t>(c)];
            v[i][c] = b.v[3 * i + static_cast<size_t>(c)];
        }
}

} // namespace fascia::cuda
