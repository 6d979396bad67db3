// The device step on a GPU: the kernel bodies of StepKernels.h wrapped in __global__ launches, one
// thread per element or node, over device copies of the StepArraysHost that the emulation uses too;
// the element kernels launched once per material group, over its element list. Kept to one file and
// to the laws of DeviceLaws.h: each law costs two element kernels (tetrahedra, hexahedra) per
// precision and variant (elastic or relaxed; for the laws that read a fibre, with fibres per element
// or not) in nvcc time.
#include "DeviceLaws.h"
#include "StepRunner.h"
#include "fascia/base/Error.h"
#include "fascia/cuda/StepKernels.h"

#include <cuda_runtime.h>

#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <string>
#include <utility>

namespace fascia::cuda {

namespace {

void check(cudaError_t e, const char* what) {
    if (e != cudaSuccess)
        core::throwSimulationError(std::string("[CudaStep] ") + what + " failed: " + cudaGetErrorName(e) + ": " + cudaGetErrorString(e));
}

// (Relaxed: with the Prony series, a kernel of its own, so that the elastic one keeps its registers;
// PerElementFibres likewise. Listed: thread k takes element list[k] of a material group; else
// element k of the whole mesh of one material, in a kernel of its own too: a list read at run time
// changed the registers of every law's kernels, by -5 to +8, ptxas on sm_90)
template <class Law, class T, bool Relaxed, bool PerElementFibres, bool Listed>
__global__ void tetKernel(StepArrays<T> d, ElementParams<Law, T> p, const int* list, int count) {
    const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if constexpr (Listed) {
        if (k < count) tetForces<Relaxed, PerElementFibres>(d, p, list[k]);
    } else if (k < d.nTets) {
        tetForces<Relaxed, PerElementFibres>(d, p, k);
    }
}

template <class Law, class T, bool Relaxed, bool PerElementFibres, bool Listed>
__global__ void hexKernel(StepArrays<T> d, ElementParams<Law, T> p, const int* list, int count) {
    const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if constexpr (Listed) {
        if (k < count) hexForces<Relaxed, PerElementFibres>(d, p, list[k]);
    } else if (k < d.nHexes) {
        hexForces<Relaxed, PerElementFibres>(d, p, k);
    }
}

template <class Law, class T, bool Relaxed, bool Listed>
__global__ void edgeKernel(StepArrays<T> d, ElementParams<Law, T> p, const int* list, int count) {
    const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if constexpr (Listed) {
        if (k < count) edgeForces<Relaxed>(d, p, list[k]);
    } else if (k < d.nTets) {
        edgeForces<Relaxed>(d, p, k);
    }
}

template <class T>
__global__ void springKernel(StepArrays<T> d) {
    const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if (k < d.nTets) springForces(d, k);
}

template <class T>
__global__ void faceKernel(StepArrays<T> d, FaceParams<T> q) {
    const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if (k < d.nTris + d.nQuads) faceForces(d, q, k);
}

template <class T>
__global__ void eulerKernel(StepArrays<T> d, NodeParams<T> p) {
    const int n = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if (n < d.nNodes) eulerStep(d, p, n);
}

template <class T>
__global__ void centralKernel(StepArrays<T> d, NodeParams<T> p) {
    const int n = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if (n < d.nNodes) centralStep(d, p, n);
}

template <class T>
__global__ void gatherKernel(StepArrays<T> d, T* f) {
    const int n = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if (n < d.nNodes) {
        const elements::Vec33<T> g = gatherForce(d, n);
        f[3 * n] = g.x;
        f[3 * n + 1] = g.y;
        f[3 * n + 2] = g.z;
    }
}

/// One device array, freed with its owner. Copies go through the runner's stream (in order with
/// its launches) and wait for their end.
template <class T>
class DeviceArray {
public:
    DeviceArray() = default;
    DeviceArray(const DeviceArray&) = delete;
    DeviceArray& operator=(const DeviceArray&) = delete;
    ~DeviceArray() {
        if (m_p) cudaFree(m_p);
    }
    void allocate(size_t n) {
        if (n == m_n) return;
        if (m_p) check(cudaFree(m_p), "cudaFree");
        m_p = nullptr;
        m_n = n;
        if (m_n) check(cudaMalloc(reinterpret_cast<void**>(&m_p), m_n * sizeof(T)), "cudaMalloc");
    }
    void upload(const T* h, size_t n, cudaStream_t s) {
        allocate(n);
        if (m_n) check(cudaMemcpyAsync(m_p, h, m_n * sizeof(T), cudaMemcpyHostToDevice, s), "cudaMemcpyAsync to the device");
        check(cudaStreamSynchronize(s), "the upload");
    }
    void upload(const std::vector<T>& h, cudaStream_t s) { upload(h.data(), h.size(), s); }
    T* data() const { return m_p; }
    size_t size() const { return m_n; }

private:
    T* m_p = nullptr;
    size_t m_n = 0;
};

/// Page-locked host memory (cudaMallocHost), so that copies run asynchronously at full speed.
template <class T>
class PinnedArray {
public:
    PinnedArray() = default;
    PinnedArray(const PinnedArray&) = delete;
    PinnedArray& operator=(const PinnedArray&) = delete;
    ~PinnedArray() {
        if (m_p) cudaFreeHost(m_p);
    }
    void allocate(size_t n) {
        if (n <= m_n) return;
        if (m_p) check(cudaFreeHost(m_p), "cudaFreeHost");
        m_p = nullptr;
        check(cudaMallocHost(reinterpret_cast<void**>(&m_p), n * sizeof(T)), "cudaMallocHost");
        m_n = n;
    }
    T* get() const { return m_p; }

private:
    T* m_p = nullptr;
    size_t m_n = 0;
};

/// The split of a step between its kernels, for tools/gpu-check.sh: with FASCIA_CUDA_TIMING=1 in
/// the environment each pass is timed by events and waited for (so the host no longer queues steps
/// ahead), and the means go to stderr when the runner ends.
class PassTimer {
public:
    PassTimer() : m_on(std::getenv("FASCIA_CUDA_TIMING") && std::string(std::getenv("FASCIA_CUDA_TIMING")) == "1") {
        if (m_on) {
            check(cudaEventCreate(&m_start), "cudaEventCreate");
            check(cudaEventCreate(&m_stop), "cudaEventCreate");
        }
    }
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;
    ~PassTimer() {
        if (!m_on) return;
        if (m_count[0] > 0)
            std::fprintf(stderr, "cuda-timing: element pass %.5f ms, node pass %.5f ms (means over %ld and %ld passes)\n",
                         m_ms[0] / double(m_count[0]), m_count[1] ? m_ms[1] / double(m_count[1]) : 0.0, m_count[0], m_count[1]);
        cudaEventDestroy(m_start);
        cudaEventDestroy(m_stop);
    }
    /// Runs launch() on stream s, timed as pass k (0 elements, 1 nodes) when timing is on.
    template <class F>
    void run(int k, cudaStream_t s, F&& launch) {
        if (m_on) check(cudaEventRecord(m_start, s), "cudaEventRecord");
        launch();
        if (!m_on) return;
        check(cudaEventRecord(m_stop, s), "cudaEventRecord");
        check(cudaEventSynchronize(m_stop), "cudaEventSynchronize");
        float ms = 0;
        check(cudaEventElapsedTime(&ms, m_start, m_stop), "cudaEventElapsedTime");
        m_ms[k] += ms;
        ++m_count[k];
    }

private:
    bool m_on;
    cudaEvent_t m_start = nullptr, m_stop = nullptr;
    double m_ms[2] = {0, 0};
    long m_count[2] = {0, 0};
};

unsigned grid(int n, int block) { return static_cast<unsigned>((n + block - 1) / block); }

/// The block size for kernel k: `block`, or less where k's registers allow fewer threads a block (a
/// law's double kernel may take 70 registers a thread: 1024 threads would not launch). The results
/// are the same for any block size.
template <class K>
int fitBlock(K k, int block) {
    cudaFuncAttributes a{};
    check(cudaFuncGetAttributes(&a, k), "cudaFuncGetAttributes");
    return a.maxThreadsPerBlock >= block ? block : a.maxThreadsPerBlock / 32 * 32;
}

/// The element kernels of one material group (StepSetup::Group), whatever its law: a runner holds
/// one per group and launches them in turn.
template <class T>
class ElementPass {
public:
    virtual ~ElementPass() = default;
    /// Its kernels over its tetrahedra and hexahedra, on stream s.
    virtual void launch(const StepArrays<T>& d, cudaStream_t s) = 0;
    /// Its Prony series (the coefficients are every group's).
    virtual PronyParams<T>& prony() = 0;
};

/// The element kernels of a group of law Law: its parameters, its element lists on the device (none
/// when the setup has one group: the kernels then run over every element), and the kernel variant
/// of the setup (relaxed with Prony series; with fibres per element where the setup has them and the
/// law reads one, so that the other laws compile no such variant).
template <class Law, class T>
class LawPass final : public ElementPass<T> {
public:
    LawPass(const StepSetup& s, const StepSetup::Group& g, const Law& law, int block, cudaStream_t stream)
        : m_p(elementParams<T>(s, g, law)) {
        if (s.groups.size() > 1) {
            m_tets.upload(g.tets, stream);
            m_hexes.upload(g.hexes, stream);
        }
        m_nTets = s.groups.size() > 1 ? static_cast<int>(g.tets.size()) : s.nTets;
        m_nHexes = s.groups.size() > 1 ? static_cast<int>(g.hexes.size()) : s.nHexes;
        const bool listed = s.groups.size() > 1, edges = s.form == StepSetup::Form::Edges;
        if (m_p.prony.series > 0) listed ? choose<true, true>(s.fibresPerElement, edges) : choose<true, false>(s.fibresPerElement, edges);
        else listed ? choose<false, true>(s.fibresPerElement, edges) : choose<false, false>(s.fibresPerElement, edges);
        m_tetBlock = fitBlock(m_tetKernel, block);
        m_hexBlock = fitBlock(m_hexKernel, block);
    }
    void launch(const StepArrays<T>& d, cudaStream_t s) override {
        if (m_nTets > 0) {
            m_tetKernel<<<grid(m_nTets, m_tetBlock), m_tetBlock, 0, s>>>(d, m_p, m_tets.data(), m_nTets);
            check(cudaGetLastError(), "the tetrahedron kernel launch");
        }
        if (m_nHexes > 0) {
            m_hexKernel<<<grid(m_nHexes, m_hexBlock), m_hexBlock, 0, s>>>(d, m_p, m_hexes.data(), m_nHexes);
            check(cudaGetLastError(), "the hexahedron kernel launch");
        }
    }
    PronyParams<T>& prony() override { return m_p.prony; }

private:
    /// The kernels of the variant: HEML's edge form on the tetrahedra (edges: its fibres are per
    /// element always), else TLED's, with fibres per element or not.
    template <bool Relaxed, bool Listed>
    void choose(bool fibres, bool edges) {
        m_hexKernel = hexKernel<Law, T, Relaxed, false, Listed>;
        if (edges) {
            m_tetKernel = edgeKernel<Law, T, Relaxed, Listed>;
            return;
        }
        if constexpr (detail::Uses<Law>::i4 || detail::Uses<Law>::i6)
            if (fibres) {
                m_tetKernel = tetKernel<Law, T, Relaxed, true, Listed>;
                m_hexKernel = hexKernel<Law, T, Relaxed, true, Listed>;
                return;
            }
        m_tetKernel = tetKernel<Law, T, Relaxed, false, Listed>;
    }
    ElementParams<Law, T> m_p;
    DeviceArray<int> m_tets, m_hexes;  ///< the group's element lists (empty: every element)
    int m_nTets = 0, m_nHexes = 0;     ///< the threads of each kernel
    using Kernel = void (*)(StepArrays<T>, ElementParams<Law, T>, const int*, int);
    Kernel m_tetKernel = nullptr, m_hexKernel = nullptr;
    int m_tetBlock = 0, m_hexBlock = 0;  ///< their block sizes (fitBlock)
};

/// HEML's mass-spring mode over every tetrahedron (StepSetup::springs: no material, no series).
template <class T>
class SpringPass final : public ElementPass<T> {
public:
    SpringPass(const StepSetup& s, int block) : m_n(s.nTets), m_block(fitBlock(springKernel<T>, block)) {}
    void launch(const StepArrays<T>& d, cudaStream_t s) override {
        if (m_n == 0) return;
        springKernel<T><<<grid(m_n, m_block), m_block, 0, s>>>(d);
        check(cudaGetLastError(), "the spring kernel launch");
    }
    PronyParams<T>& prony() override { return m_none; }

private:
    int m_n, m_block;
    PronyParams<T> m_none;
};

/// The device step of one body: its arrays on the device, its launches on a stream of its own. The
/// host queues steps without waiting for them; it waits only to read something back (the state,
/// the forces, the record of a state that is not finite) and when it reuses the pinned buffer of
/// the targets it uploaded two steps before.
template <class T>
class CudaRunner final : public StepRunner {
public:
    CudaRunner(const StepSetup& s, int block) : m_block(block), m_central(s.scheme == StepSetup::Scheme::CentralDifference) {
        check(cudaStreamCreateWithFlags(&m_stream, cudaStreamNonBlocking), "cudaStreamCreate");
        for (cudaEvent_t& e : m_targetsCopied) check(cudaEventCreateWithFlags(&e, cudaEventDisableTiming), "cudaEventCreate");
        upload(toArrays<T>(s));
        requireLayout(layoutErrors(s));
        forEachGroupLaw(s, [&](const auto& law, const StepSetup::Group& g) {
            m_passes.push_back(std::make_unique<LawPass<std::decay_t<decltype(law)>, T>>(s, g, law, block, m_stream));
        });
        if (s.springs) m_passes.push_back(std::make_unique<SpringPass<T>>(s, block));
    }
    ~CudaRunner() override {
        cudaStreamSynchronize(m_stream);
        for (cudaEvent_t e : m_targetsCopied) cudaEventDestroy(e);
        cudaStreamDestroy(m_stream);
    }
    void setState(const std::vector<double>& u, const std::vector<double>& v) override {
        m_a.u.upload(std::vector<T>(u.begin(), u.end()), m_stream);
        m_a.v.upload(std::vector<T>(v.begin(), v.end()), m_stream);
        check(cudaMemcpyAsync(m_a.bad.data(), &kNone, sizeof kNone, cudaMemcpyHostToDevice, m_stream), "cudaMemcpyAsync to the device");
        wait();
    }
    void getState(std::vector<double>& u, std::vector<double>& v, std::vector<double>& r) override {
        const size_t n = m_a.u.size();
        const T* h = staged({{m_a.u.data(), n}, {m_a.v.data(), n}, {m_a.react.data(), n}});
        u.assign(h, h + n);
        v.assign(h + n, h + 2 * n);
        r.assign(h + 2 * n, h + 3 * n);
    }
    void getIncrements(std::vector<double>& du) override {
        const T* h = staged({{m_a.du.data(), m_a.du.size()}});
        du.assign(h, h + m_a.du.size());
    }
    void setIncrements(const std::vector<double>& du) override { m_a.du.upload(std::vector<T>(du.begin(), du.end()), m_stream); }
    void getPronyStates(std::vector<double>& Y) override {
        const T* h = staged({{m_a.Y.data(), m_a.Y.size()}, {m_a.hY.data(), m_a.hY.size()}});
        Y.assign(h, h + m_a.Y.size() + m_a.hY.size());
    }
    void setPronyStates(const std::vector<double>& Y) override {
        const size_t n = m_a.Y.size();
        const std::vector<T> y(Y.begin(), Y.end());
        m_a.Y.upload(y.data(), n, m_stream);
        m_a.hY.upload(y.data() + n, y.size() - n, m_stream);
    }
    void setRelaxation(const std::vector<double>& A, const std::vector<double>& B) override {
        for (const auto& pass : m_passes) setCoefficients(pass->prony(), A, B);
    }
    void setPressures(const FaceParams<double>& q) override { m_q = faceParamsIn<T>(q); }
    void elementPass() override {
        m_timer.run(0, m_stream, [&] {
            for (const auto& pass : m_passes) pass->launch(m_d, m_stream);
            if (m_d.nTris + m_d.nQuads > 0) {
                faceKernel<T><<<grid(m_d.nTris + m_d.nQuads), m_block, 0, m_stream>>>(m_d, m_q);
                check(cudaGetLastError(), "the face kernel launch");
            }
        });
    }
    void setTargets(const std::vector<double>& tu, const std::vector<double>& tv) override {
        // two pinned buffers in turn: the one written now was last copied two steps ago
        const size_t n = tu.size(), k = m_nextTargets;
        m_nextTargets ^= 1;
        check(cudaEventSynchronize(m_targetsCopied[k]), "the copy of earlier targets");
        m_targets[k].allocate(2 * n);
        T* h = m_targets[k].get();
        for (size_t j = 0; j < n; ++j) h[j] = static_cast<T>(tu[j]), h[n + j] = static_cast<T>(tv[j]);
        check(cudaMemcpyAsync(m_a.tu.data(), h, n * sizeof(T), cudaMemcpyHostToDevice, m_stream), "cudaMemcpyAsync of the targets");
        check(cudaMemcpyAsync(m_a.tv.data(), h + n, n * sizeof(T), cudaMemcpyHostToDevice, m_stream), "cudaMemcpyAsync of the targets");
        check(cudaEventRecord(m_targetsCopied[k], m_stream), "cudaEventRecord");
    }
    void nodePass(const NodeParams<double>& p) override {
        const NodeParams<T> q = nodeParamsIn<T>(p);
        m_timer.run(1, m_stream, [&] {
            if (m_central) centralKernel<T><<<grid(m_d.nNodes), m_block, 0, m_stream>>>(m_d, q);
            else eulerKernel<T><<<grid(m_d.nNodes), m_block, 0, m_stream>>>(m_d, q);
            check(cudaGetLastError(), "the node kernel launch");
        });
    }
    void internalForces(std::vector<double>& f) override {
        gatherKernel<T><<<grid(m_d.nNodes), m_block, 0, m_stream>>>(m_d, m_f.data());
        check(cudaGetLastError(), "the gather kernel launch");
        const T* h = staged({{m_f.data(), m_f.size()}});
        f.assign(h, h + m_f.size());
    }
    long firstBadStep() override {
        m_flag.allocate(1);
        check(cudaMemcpyAsync(m_flag.get(), m_a.bad.data(), sizeof kNone, cudaMemcpyDeviceToHost, m_stream), "cudaMemcpyAsync to the host");
        wait();
        return *m_flag.get() == kNone ? -1 : static_cast<long>(*m_flag.get());
    }
    void wait() override { check(cudaStreamSynchronize(m_stream), "the device step"); }
    std::vector<std::string> layoutErrors(const StepSetup& s) override { return checkLayout(s, m_d, m_a); }

private:
    static constexpr unsigned long long kNone = ~0ull;
    unsigned grid(int n) const { return fascia::cuda::grid(n, m_block); }
    /// Device arrays (pointer, length), after every step launched so far, one after the other in
    /// the pinned stage, which it returns (valid until the next call).
    const T* staged(std::initializer_list<std::pair<const T*, size_t>> parts) {
        size_t total = 0;
        for (const auto& [from, n] : parts) total += n;
        m_stage.allocate(total);
        T* to = m_stage.get();
        for (const auto& [from, n] : parts) {
            if (n) check(cudaMemcpyAsync(to, from, n * sizeof(T), cudaMemcpyDeviceToHost, m_stream), "cudaMemcpyAsync to the host");
            to += n;
        }
        wait();
        return m_stage.get();
    }
    /// The arrays of h on the device, and m_d pointing at them: each row of the table
    /// (FASCIA_STEP_ARRAYS, StepLayout.h).
    void upload(const StepArraysHost<T>& h) {
        static_cast<StepCounts&>(m_d) = h;
        forEachStepArray<T>(
            [&](const StepArrayInfo&, auto at, auto, const auto& from, auto& to) {
                to.upload(from, m_stream);
                m_d.*at = to.data();
            },
            h, m_a);
        m_f.upload(h.u, m_stream);  // (the gathered forces of internalForces, 3 per node)
    }
    int m_block;
    bool m_central;
    cudaStream_t m_stream = nullptr;
    StepStores<T, DeviceArray> m_a;  ///< the arrays of m_d on the device, a buffer per row of the table
    DeviceArray<T> m_f;              ///< the forces internalForces gathers
    PinnedArray<T> m_stage, m_targets[2];
    PinnedArray<unsigned long long> m_flag;
    cudaEvent_t m_targetsCopied[2] = {nullptr, nullptr};
    int m_nextTargets = 0;
    PassTimer m_timer;
    StepArrays<T> m_d;
    std::vector<std::unique_ptr<ElementPass<T>>> m_passes;  ///< one per material group (StepSetup::groups), or the springs
    FaceParams<T> m_q;  ///< the pressures of the step (setPressures)
};

} // namespace

std::unique_ptr<StepRunner> makeCudaRunner(const StepSetup& s, Precision p, int block) {
    if (p == Precision::Float) return std::make_unique<CudaRunner<float>>(s, block);
    return std::make_unique<CudaRunner<double>>(s, block);
}

int cudaDevices(std::string& why) {
    int n = 0;
    const cudaError_t e = cudaGetDeviceCount(&n);
    if (e != cudaSuccess) {
        why = std::string("cudaGetDeviceCount: ") + cudaGetErrorName(e) + ": " + cudaGetErrorString(e);
        return 0;
    }
    if (n == 0) {
        why = "no CUDA device";
        return 0;
    }
    cudaDeviceProp prop;
    if (cudaGetDeviceProperties(&prop, 0) == cudaSuccess) why = prop.name;
    return n;
}

} // namespace fascia::cuda
