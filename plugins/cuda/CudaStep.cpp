#include "CudaStep.h"

#include "fascia/base/StateIO.h"
#include "fascia/elements/Errors.h"

#include <algorithm>

namespace fascia::cuda {

void CudaStep::adopt(core::MechanicalGroup& g) {
    Body b;
    b.state = g.state;
    // every component is checked before the device: a scene the GPU cannot run says so anywhere
    b.setup = buildStepSetup(*this, g);
    b.setup.forcesInNodeOrder = m_forceOrder.get() == "node";
    const Precision p = m_precision.get() == "float" ? Precision::Float : Precision::Double;
    b.precision = p;
    if (m_emulate.get()) {
        b.runner = makeEmulatedRunner(b.setup, p);
    } else {
        std::string why;
        if (cudaDevices(why) == 0)
            fail("no usable CUDA device (" + why + ")", {"run on a machine with an NVIDIA GPU and its driver, or remove CudaStep to run on the CPU"});
        b.runner = makeCudaRunner(b.setup, p, m_blockSize.get());
    }
    b.kick.halfStepStart = b.setup.halfStepStart;
    if (!b.setup.series.empty()) b.history = dynamic_cast<viscoelastic::ElementHistory*>(b.setup.elastic);
    b.du.assign(3 * g.state->size(), 0.0);
    upload(b, g);
    m_bodies.push_back(std::move(b));
}

CudaStep::Body& CudaStep::body(const core::MechanicalGroup& g) {
    auto it = std::find_if(m_bodies.begin(), m_bodies.end(), [&](const Body& b) { return b.state == g.state; });
    if (it == m_bodies.end()) elements::runtimeError(*this, "the state '" + g.state->path() + "' was not adopted at init");
    return *it;
}

void CudaStep::upload(Body& b, const core::MechanicalGroup& g) {
    const size_t n = g.state->size();
    b.u.resize(3 * n);
    b.v.resize(3 * n);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            b.u[3 * i + static_cast<size_t>(c)] = g.state->x()[i][c] - g.state->x0()[i][c];
            b.v[3 * i + static_cast<size_t>(c)] = g.state->v()[i][c];
        }
    b.runner->setState(b.u, b.v);
    b.xSeen = g.state->x();
    b.vSeen = g.state->v();
    b.onHost = true;
}

void CudaStep::step(core::MechanicalGroup& g, double t, double dt) {
    Body& b = body(g);
    // a program may have written the state it read (or set before the first step): the device
    // takes what is there
    if (b.onHost && (g.state->x() != b.xSeen || g.state->v() != b.vSeen)) upload(b, g);
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
    if (!b.setup.pressures.empty()) b.runner->setPressures(faceParams<double>(b.setup, t));
    b.runner->elementPass();
    NodeParams<double> p = nodeParams(g, b.setup, t, dt, b.kick.next(dt));
    p.step = static_cast<unsigned long long>(g.stepIndex);
    b.central.next(dt, p);
    if (!b.setup.targetAt.empty()) {
        motionTargets(g, b.setup, t + dt, b.tu, b.tv);
        b.runner->setTargets(b.tu, b.tv);
    }
    b.runner->nodePass(p);
    b.onHost = false;
    if (g.stepIndex % m_checkEvery.get() == 0) check(b, g);
}

void CudaStep::check(Body& b, core::MechanicalGroup& g) {
    const long bad = b.runner->firstBadStep();
    if (bad < 0) return;
    g.firstBadStep = bad;
    elements::runtimeError(*this, "step " + std::to_string(g.stepIndex) + ": the state '" + g.state->path() +
                                      "' is not finite on the device since step " + std::to_string(bad) +
                                      " (found then: the host reads the device's record every " + std::to_string(m_checkEvery.get()) +
                                      " steps, checkEvery, and whenever it reads the state); a smaller dt, or dt=\"auto\", keeps an "
                                      "explicit step stable");
}

void CudaStep::fetch(core::MechanicalGroup& g) {
    Body& b = body(g);
    if (b.onHost) return;
    check(b, g);
    b.runner->getState(b.u, b.v, b.r);
    Positions& x = g.state->x();
    Positions& v = g.state->v();
    Positions& r = g.state->reaction();
    const Positions& X = g.state->x0();
    r.resize(x.size());
    for (size_t i = 0; i < x.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const size_t k = 3 * i + static_cast<size_t>(c);
            x[i][c] = X[i][c] + b.u[k];
            v[i][c] = b.v[k];
            r[i][c] = b.r[k];  // (the reactions of the step's start, as MechanicalGroup::computeForces leaves them)
        }
    if (b.history) {
        // the stress output of the element force field reads the device's Prony states
        std::vector<double> Y, Yh;
        b.runner->getPronyStates(Y);
        const size_t nt = 6 * static_cast<size_t>(b.setup.pronyTerms()) * static_cast<size_t>(b.setup.nTets);
        Yh.assign(Y.begin() + static_cast<std::ptrdiff_t>(nt), Y.end());
        Y.resize(nt);
        b.history->adoptHistory(Y, Yh, b.clock);
    }
    b.xSeen = x;
    b.vSeen = v;
    b.onHost = true;
}

void CudaStep::push(core::MechanicalGroup& g) {
    Body& b = body(g);
    if (b.restored) {
        b.restored = false;
        b.runner->setState(b.u, b.v);
        b.runner->setPronyStates(b.Y);
        b.xSeen = g.state->x();
        b.vSeen = g.state->v();
        b.onHost = true;
    } else {
        upload(b, g);
    }
    b.runner->setIncrements(b.du);
}

void CudaStep::wait() {
    for (Body& b : m_bodies) b.runner->wait();
}

core::LayoutBytes CudaStep::layoutBytes() const {
    core::LayoutBytes out;
    for (const Body& b : m_bodies) {
        // (the rule of core::LayoutBytes: an array counts once, and once more for each pass writing it)
        const size_t T = b.precision == Precision::Float ? 4 : 8, I = 4;
        const size_t nT = static_cast<size_t>(b.setup.nTets), nH = static_cast<size_t>(b.setup.nHexes);
        const size_t n = static_cast<size_t>(b.setup.nNodes);
        const bool central = b.setup.scheme == StepSetup::Scheme::CentralDifference;
        // element kernels: connectivity, rest data, and the forces of their slots, written, then read
        // by the node kernel
        // (tetrahedra: TLED's dN and volume, or HEML's rest edges, G, 1 / det V, volume and the
        // fibres' V^-1 a0 or the springs' shares and rest lengths)
        const StepSetup& st = b.setup;
        const size_t tetRest = st.form == StepSetup::Form::TLED
                                   ? 10 * nT
                                   : st.eV.size() + st.eG.size() + st.eInvDetV.size() + st.vol.size() + st.ew4.size() + st.ew6.size() +
                                         st.ekk.size() + st.elen0.size();
        out.elementData += nT * (4 * I + 2 * 12 * T) + tetRest * T + nH * (8 * I + 38 * T + 2 * 24 * T);
        // the Prony states, read and written in place
        out.elementData += (nT + nH) * 2 * 6 * static_cast<size_t>(b.setup.pronyTerms()) * T;
        // the fibre directions per element (3 per direction), and the groups' element lists
        out.elementData += (b.setup.fa.size() + b.setup.fb.size() + b.setup.hfa.size() + b.setup.hfb.size()) * T;
        if (b.setup.groups.size() > 1) out.elementData += (nT + nH) * I;
        // node kernel: u and v read and written (u also read by the element kernels), masses,
        // external forces, hold codes, the increments of CentralDifference
        out.nodeRows += n * (2 * 3 * T + 2 * 3 * T + 2 * T + 3 * T + 3 * I + (central ? 2 * 3 * T : 0));
        // the faces under pressure: corners, rest differences, load index, their forces written and read
        const size_t nTri = static_cast<size_t>(b.setup.nTris), nQ = static_cast<size_t>(b.setup.nQuads);
        out.elementData += nTri * (4 * I + 6 * T + 2 * 3 * T) + nQ * (5 * I + 9 * T + 2 * 12 * T);
        // the slot lists of the gather
        out.buffers += (n + 1) * I + (4 * nT + 8 * nH + 3 * nTri + 4 * nQ) * I;
        // in node order: each corner reads its slot's position (and a triangle writes its force 3 times)
        if (st.forcesInNodeOrder) out.buffers += (4 * nT + 8 * nH + 3 * nTri + 4 * nQ) * I + nTri * 2 * 2 * 3 * T;
    }
    return out;
}

void CudaStep::saveState(core::StateWriter& out) const {
    out.put("bodies", long(m_bodies.size()));
    for (const Body& b : m_bodies) {
        out.put("state", b.state->path());
        out.put("kickStarted", b.kick.started);
        out.put("kickLastDt", b.kick.lastDt);
        out.put("centralStarted", b.central.started);
        out.put("centralLastDt", b.central.lastDt);
        out.put("centralSteps", b.central.steps);
        // (the core fetched the state before: u and v are the device's)
        out.put("u", b.u);
        out.put("v", b.v);
        std::vector<double> du;
        b.runner->getIncrements(du);
        out.put("increments", du);
        std::vector<double> Y;
        b.runner->getPronyStates(Y);
        out.put("prony", Y);
        b.clock.save(out);
        out.put("pronyA", b.A);
        out.put("pronyB", b.B);
    }
}

void CudaStep::restoreState(core::StateReader& in) {
    const long n = in.getLong("bodies");
    if (n != long(m_bodies.size()))
        in.fail("[" + path() + "] the checkpoint has " + std::to_string(n) + " bodies on the device, this scene " +
                std::to_string(m_bodies.size()));
    for (Body& b : m_bodies) {
        const std::string s = in.getText("state");
        if (s != b.state->path()) in.fail("[" + path() + "] the checkpoint's body '" + s + "' is not '" + b.state->path() + "'");
        b.kick.started = in.getBool("kickStarted");
        b.kick.lastDt = in.getDouble("kickLastDt");
        b.central.started = in.getBool("centralStarted");
        b.central.lastDt = in.getDouble("centralLastDt");
        b.central.steps = in.getLong("centralSteps");
        in.getInto("u", b.u.data(), b.u.size());
        in.getInto("v", b.v.data(), b.v.size());
        in.getInto("increments", b.du.data(), b.du.size());
        b.Y = in.getDoubles("prony");
        const size_t states = 6 * static_cast<size_t>(b.setup.pronyTerms()) * static_cast<size_t>(b.setup.nTets + b.setup.nHexes);
        if (b.Y.size() != states)
            in.fail("[" + path() + "] the checkpoint holds " + std::to_string(b.Y.size()) + " Prony states for '" + b.state->path() +
                    "', this scene " + std::to_string(states));
        b.clock.restore(in);
        b.A = in.getDoubles("pronyA");
        b.B = in.getDoubles("pronyB");
        if (!b.A.empty()) b.runner->setRelaxation(b.A, b.B);
        b.restored = true;  // (uploaded by push, after every component read its records)
    }
}

} // namespace fascia::cuda
