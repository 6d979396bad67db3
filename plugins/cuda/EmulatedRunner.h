#pragma once
/// The device step on the CPU: the kernel bodies of StepKernels.h called in loops, one call per
/// element or node, over "device" arrays that are host vectors uploaded (copied) from the same
/// StepArraysHost the GPU path copies to the device. Slow (no vectorisation, one thread): for tests.
#include "StepRunner.h"
#include "fascia/cuda/StepKernels.h"

namespace fascia::cuda {

template <class Law, class T>
class EmulatedRunner final : public StepRunner {
public:
    EmulatedRunner(const StepSetup& s, const Law& law) : m_dev(toArrays<T>(s)), m_central(s.scheme == StepSetup::Scheme::CentralDifference) {
        m_p.law = law;
        m_p.J0 = static_cast<T>(s.J0);
        m_p.a0 = {T(s.a0.x), T(s.a0.y), T(s.a0.z)};
        m_p.b0 = {T(s.b0.x), T(s.b0.y), T(s.b0.z)};
        m_p.prony = pronyParams<T>(s);
    }
    void setState(const std::vector<double>& u, const std::vector<double>& v) override {
        m_dev.u.assign(u.begin(), u.end());
        m_dev.v.assign(v.begin(), v.end());
        m_dev.bad = ~0ull;
    }
    void getState(std::vector<double>& u, std::vector<double>& v) override {
        u.assign(m_dev.u.begin(), m_dev.u.end());
        v.assign(m_dev.v.begin(), m_dev.v.end());
    }
    void getPronyStates(std::vector<double>& Y) override {
        Y.assign(m_dev.Y.begin(), m_dev.Y.end());
        Y.insert(Y.end(), m_dev.hY.begin(), m_dev.hY.end());
    }
    void setPronyStates(const std::vector<double>& Y) override {
        const size_t n = m_dev.Y.size();
        m_dev.Y.assign(Y.begin(), Y.begin() + static_cast<std::ptrdiff_t>(n));
        m_dev.hY.assign(Y.begin() + static_cast<std::ptrdiff_t>(n), Y.end());
    }
    void getIncrements(std::vector<double>& du) override { du.assign(m_dev.du.begin(), m_dev.du.end()); }
    void setIncrements(const std::vector<double>& du) override { m_dev.du.assign(du.begin(), du.end()); }
    long firstBadStep() override { return m_dev.bad == ~0ull ? -1 : static_cast<long>(m_dev.bad); }
    void wait() override {}
    void elementPass() override {
        const StepArrays<T> d = m_dev.view();
        if (m_p.prony.series > 0) {
            for (int e = 0; e < d.nTets; ++e) tetForces<true>(d, m_p, e);
            for (int e = 0; e < d.nHexes; ++e) hexForces<true>(d, m_p, e);
            facePass(d);
            return;
        }
        for (int e = 0; e < d.nTets; ++e) tetForces(d, m_p, e);
        for (int e = 0; e < d.nHexes; ++e) hexForces(d, m_p, e);
        facePass(d);
    }
    void setPressures(const FaceParams<double>& q) override {
        for (int k = 0; k < kMaxPressures; ++k) m_q.p[k] = static_cast<T>(q.p[k]);
    }
    void setRelaxation(const std::vector<double>& A, const std::vector<double>& B) override { setCoefficients(m_p.prony, A, B); }
    void setTargets(const std::vector<double>& tu, const std::vector<double>& tv) override {
        m_dev.tu.assign(tu.begin(), tu.end());
        m_dev.tv.assign(tv.begin(), tv.end());
    }
    void nodePass(const NodeParams<double>& p) override {
        const StepArrays<T> d = m_dev.view();
        const NodeParams<T> q = nodeParamsIn<T>(p);
        for (int n = 0; n < d.nNodes; ++n) {
            if (m_central) centralStep(d, q, n);
            else eulerStep(d, q, n);
        }
    }
    void internalForces(std::vector<double>& f) override {
        const StepArrays<T> d = m_dev.view();
        f.resize(3 * static_cast<size_t>(d.nNodes));
        for (int n = 0; n < d.nNodes; ++n) {
            const elements::Vec33<T> g = gatherForce(d, n);
            f[3 * static_cast<size_t>(n)] = g.x;
            f[3 * static_cast<size_t>(n) + 1] = g.y;
            f[3 * static_cast<size_t>(n) + 2] = g.z;
        }
    }

private:
    void facePass(const StepArrays<T>& d) {
        for (int k = 0; k < d.nTris + d.nQuads; ++k) faceForces(d, m_q, k);
    }
    StepArraysHost<T> m_dev;
    FaceParams<T> m_q;  ///< the "device" copy
    bool m_central;           ///< CentralDifference, else SemiImplicitEuler
    ElementParams<Law, T> m_p;
};

} // namespace fascia::cuda
