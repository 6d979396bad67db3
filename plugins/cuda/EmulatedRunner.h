#pragma once
/// The device step on the CPU: the kernel bodies of StepKernels.h called in loops, one call per
/// element or node, over "device" arrays that are host vectors uploaded (copied) from the same
/// StepArraysHost the GPU path copies to the device, the element kernels of each material group
/// over its element list as the GPU launches them. Slow (no vectorisation, one thread): for tests.
#include "StepRunner.h"
#include "fascia/cuda/StepKernels.h"

namespace fascia::cuda {

/// The emulation's "device" copy of h: each array of the table (FASCIA_STEP_ARRAYS, StepLayout.h)
/// copied, as CudaRunner.cu uploads them.
template <class T>
StepArraysHost<T> emulatedUpload(const StepArraysHost<T>& h) {
    StepArraysHost<T> dev;
    static_cast<StepCounts&>(dev) = h;
    forEachStepArray<T>([](const StepArrayInfo&, auto, auto, const auto& from, auto& to) { to = from; }, h, dev);
    return dev;
}

template <class T>
class EmulatedRunner final : public StepRunner {
public:
    explicit EmulatedRunner(const StepSetup& s) : m_dev(emulatedUpload(toArrays<T>(s))), m_central(s.scheme == StepSetup::Scheme::CentralDifference) {
        requireLayout(layoutErrors(s));
        forEachGroupLaw(s, [&](const auto& law, const StepSetup::Group& g) {
            m_passes.push_back(std::make_unique<LawPass<std::decay_t<decltype(law)>>>(s, g, law));
        });
        if (s.springs) m_passes.push_back(std::make_unique<SpringPass>());
    }
    void setState(const std::vector<double>& u, const std::vector<double>& v) override {
        m_dev.u.assign(u.begin(), u.end());
        m_dev.v.assign(v.begin(), v.end());
        m_dev.bad[0] = ~0ull;
    }
    void getState(std::vector<double>& u, std::vector<double>& v, std::vector<double>& r) override {
        u.assign(m_dev.u.begin(), m_dev.u.end());
        v.assign(m_dev.v.begin(), m_dev.v.end());
        r.assign(m_dev.react.begin(), m_dev.react.end());
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
    long firstBadStep() override { return m_dev.bad[0] == ~0ull ? -1 : static_cast<long>(m_dev.bad[0]); }
    std::vector<std::string> layoutErrors(const StepSetup& s) override { return checkLayout(s, m_dev.view(), m_dev); }
    void wait() override {}
    void elementPass() override {
        const StepArrays<T> d = m_dev.view();
        for (const auto& pass : m_passes) pass->run(d);
        for (int k = 0; k < d.nTris + d.nQuads; ++k) faceForces(d, m_q, k);
    }
    void setPressures(const FaceParams<double>& q) override { m_q = faceParamsIn<T>(q); }
    void setRelaxation(const std::vector<double>& A, const std::vector<double>& B) override {
        for (const auto& pass : m_passes) setCoefficients(pass->prony(), A, B);
    }
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
    /// The element kernels of one material group, whatever its law.
    struct Pass {
        virtual ~Pass() = default;
        virtual void run(const StepArrays<T>& d) = 0;
        virtual PronyParams<T>& prony() = 0;
    };
    /// Those of a group of law Law: the kernel bodies called over the group's element lists (every
    /// element with one group), relaxed with Prony series, with fibres per element where the setup
    /// has them and the law reads one (the kernels CudaRunner.cu launches).
    template <class Law>
    struct LawPass final : Pass {
        LawPass(const StepSetup& s, const StepSetup::Group& g, const Law& law)
            : p(elementParams<T>(s, g, law)), listed(s.groups.size() > 1), tets(g.tets), hexes(g.hexes),
              fibres(s.fibresPerElement && (detail::Uses<Law>::i4 || detail::Uses<Law>::i6)), edges(s.form == StepSetup::Form::Edges) {}
        void run(const StepArrays<T>& d) override {
            if (p.prony.series > 0) fibres ? loop<true, true>(d) : loop<true, false>(d);
            else fibres ? loop<false, true>(d) : loop<false, false>(d);
        }
        PronyParams<T>& prony() override { return p.prony; }
        /// one call per element as one thread per element: thread k takes element k, or the k-th of the list
        template <bool Relaxed, bool PerElementFibres>
        void loop(const StepArrays<T>& d) const {
            const int nT = listed ? static_cast<int>(tets.size()) : d.nTets, nH = listed ? static_cast<int>(hexes.size()) : d.nHexes;
            for (int k = 0; k < nT; ++k) {
                const int e = listed ? tets[static_cast<size_t>(k)] : k;
                if (edges) edgeForces<Relaxed>(d, p, e);  // (HEML: its fibres are per element always, in ew4, ew6)
                else tetForces<Relaxed, PerElementFibres>(d, p, e);
            }
            for (int k = 0; k < nH; ++k) hexForces<Relaxed, PerElementFibres>(d, p, listed ? hexes[static_cast<size_t>(k)] : k);
        }
        ElementParams<Law, T> p;
        bool listed;
        std::vector<int> tets, hexes;
        bool fibres;
        bool edges;  ///< HEML's edge form on the tetrahedra (StepSetup::Form::Edges)
    };
    /// HEML's mass-spring mode over every tetrahedron.
    struct SpringPass final : Pass {
        void run(const StepArrays<T>& d) override {
            for (int e = 0; e < d.nTets; ++e) springForces(d, e);
        }
        PronyParams<T>& prony() override { return none; }
        PronyParams<T> none;  ///< (no series in this mode)
    };
    StepArraysHost<T> m_dev;  ///< the "device" copy
    FaceParams<T> m_q;        ///< the pressures of the step (setPressures)
    bool m_central;           ///< CentralDifference, else SemiImplicitEuler
    std::vector<std::unique_ptr<Pass>> m_passes;  ///< one per material group (StepSetup::groups), or the springs
};

} // namespace fascia::cuda
