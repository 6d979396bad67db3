// The device step on a GPU: the kernel bodies of StepKernels.h wrapped in __global__ launches, one
// thread per element or node, over device copies of the StepArraysHost that the emulation uses too.
// Kept to one file and to the laws of DeviceLaws.h: each law costs two element kernels
// (tetrahedra, hexahedra) per precision in nvcc time.
#include "DeviceLaws.h"
#include "StepRunner.h"
#include "fascia/base/Error.h"
#include "fascia/cuda/StepKernels.h"

#include <cuda_runtime.h>

#include <string>

namespace fascia::cuda {

namespace {

void check(cudaError_t e, const char* what) {
    if (e != cudaSuccess)
        core::throwSimulationError(std::string("[CudaStep] ") + what + " failed: " + cudaGetErrorName(e) + ": " + cudaGetErrorString(e));
}

// (Relaxed: with the Prony series, a kernel of its own, so that the elastic one keeps its registers)
template <class Law, class T, bool Relaxed = false>
__global__ void tetKernel(StepArrays<T> d, ElementParams<Law, T> p) {
    const int e = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if (e < d.nTets) tetForces<Relaxed>(d, p, e);
}

template <class Law, class T, bool Relaxed = false>
__global__ void hexKernel(StepArrays<T> d, ElementParams<Law, T> p) {
    const int e = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
    if (e < d.nHexes) hexForces<Relaxed>(d, p, e);
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

/// One device array, freed with its owner.
template <class T>
class DeviceArray {
public:
    DeviceArray() = default;
    DeviceArray(const DeviceArray&) = delete;
    DeviceArray& operator=(const DeviceArray&) = delete;
    ~DeviceArray() {
        if (m_p) cudaFree(m_p);
    }
    void upload(const std::vector<T>& h) {
        if (h.size() != m_n) {
            if (m_p) check(cudaFree(m_p), "cudaFree");
            m_p = nullptr;
            m_n = h.size();
            if (m_n) check(cudaMalloc(reinterpret_cast<void**>(&m_p), m_n * sizeof(T)), "cudaMalloc");
        }
        if (m_n) check(cudaMemcpy(m_p, h.data(), m_n * sizeof(T), cudaMemcpyHostToDevice), "cudaMemcpy to the device");
    }
    void download(std::vector<T>& h) const {
        h.resize(m_n);
        if (m_n) check(cudaMemcpy(h.data(), m_p, m_n * sizeof(T), cudaMemcpyDeviceToHost), "cudaMemcpy to the host");
    }
    T* get() const { return m_p; }

private:
    T* m_p = nullptr;
    size_t m_n = 0;
};

template <class Law, class T>
class CudaRunner final : public StepRunner {
public:
    CudaRunner(const StepSetup& s, const Law& law, int block) : m_block(block), m_central(s.scheme == StepSetup::Scheme::CentralDifference) {
        const StepArraysHost<T> h = toArrays<T>(s);
        m_tet.upload(h.tet);
        m_slotStart.upload(h.slotStart);
        m_slots.upload(h.slots);
        m_dN.upload(h.dN);
        m_vol.upload(h.vol);
        m_ef.upload(h.ef);
        m_hex.upload(h.hex);
        m_hdN.upload(h.hdN);
        m_hgC.upload(h.hgC);
        m_hvol.upload(h.hvol);
        m_hgK.upload(h.hgK);
        m_hef.upload(h.hef);
        m_Y.upload(h.Y);
        m_hY.upload(h.hY);
        m_ext.upload(h.ext);
        m_mass.upload(h.mass);
        m_invMass.upload(h.invMass);
        m_u.upload(h.u);
        m_v.upload(h.v);
        m_hold.upload(h.hold);
        m_tu.upload(h.tu);
        m_tv.upload(h.tv);
        m_du.upload(h.du);
        m_f.upload(h.u);
        m_d.nTets = h.nTets;
        m_d.nNodes = h.nNodes;
        m_d.tet = m_tet.get();
        m_d.dN = m_dN.get();
        m_d.vol = m_vol.get();
        m_d.ef = m_ef.get();
        m_d.nHexes = h.nHexes;
        m_d.hex = m_hex.get();
        m_d.hdN = m_hdN.get();
        m_d.hgC = m_hgC.get();
        m_d.hvol = m_hvol.get();
        m_d.hgK = m_hgK.get();
        m_d.hef = m_hef.get();
        m_d.Y = m_Y.get();
        m_d.hY = m_hY.get();
        m_d.slotStart = m_slotStart.get();
        m_d.slots = m_slots.get();
        m_d.ext = m_ext.get();
        m_d.mass = m_mass.get();
        m_d.invMass = m_invMass.get();
        m_d.hold = m_hold.get();
        m_d.tu = m_tu.get();
        m_d.tv = m_tv.get();
        m_d.u = m_u.get();
        m_d.v = m_v.get();
        m_d.du = m_du.get();
        m_p.law = law;
        m_p.J0 = static_cast<T>(s.J0);
        m_p.a0 = {T(s.a0.x), T(s.a0.y), T(s.a0.z)};
        m_p.b0 = {T(s.b0.x), T(s.b0.y), T(s.b0.z)};
        m_p.prony = pronyParams<T>(s);
        if (m_p.prony.series > 0) {
            m_tetKernel = tetKernel<Law, T, true>;
            m_hexKernel = hexKernel<Law, T, true>;
        }
    }
    void setState(const std::vector<double>& u, const std::vector<double>& v) override {
        m_u.upload(std::vector<T>(u.begin(), u.end()));
        m_v.upload(std::vector<T>(v.begin(), v.end()));
    }
    void getState(std::vector<double>& u, std::vector<double>& v) override {
        std::vector<T> a, b;
        m_u.download(a);
        m_v.download(b);
        u.assign(a.begin(), a.end());
        v.assign(b.begin(), b.end());
    }
    void elementPass() override {
        if (m_d.nTets > 0) {
            m_tetKernel<<<grid(m_d.nTets), m_block>>>(m_d, m_p);
            check(cudaGetLastError(), "the tetrahedron kernel launch");
        }
        if (m_d.nHexes > 0) {
            m_hexKernel<<<grid(m_d.nHexes), m_block>>>(m_d, m_p);
            check(cudaGetLastError(), "the hexahedron kernel launch");
        }
    }
    void setRelaxation(const std::vector<double>& A, const std::vector<double>& B) override { setCoefficients(m_p.prony, A, B); }
    void setTargets(const std::vector<double>& tu, const std::vector<double>& tv) override {
        // (the same sizes as at the upload above: the device pointers stay)
        m_tu.upload(std::vector<T>(tu.begin(), tu.end()));
        m_tv.upload(std::vector<T>(tv.begin(), tv.end()));
    }
    void nodePass(const NodeParams<double>& p) override {
        const NodeParams<T> q = nodeParamsIn<T>(p);
        if (m_central) centralKernel<T><<<grid(m_d.nNodes), m_block>>>(m_d, q);
        else eulerKernel<T><<<grid(m_d.nNodes), m_block>>>(m_d, q);
        check(cudaGetLastError(), "the node kernel launch");
    }
    void internalForces(std::vector<double>& f) override {
        gatherKernel<T><<<grid(m_d.nNodes), m_block>>>(m_d, m_f.get());
        check(cudaGetLastError(), "the gather kernel launch");
        std::vector<T> h;
        m_f.download(h);
        f.assign(h.begin(), h.end());
    }

private:
    unsigned grid(int n) const { return static_cast<unsigned>((n + m_block - 1) / m_block); }
    int m_block;
    DeviceArray<int> m_tet, m_hex, m_slotStart;
    DeviceArray<std::uint32_t> m_slots;
    DeviceArray<T> m_dN, m_vol, m_ef, m_hdN, m_hgC, m_hvol, m_hgK, m_hef, m_Y, m_hY, m_ext, m_mass, m_invMass, m_u, m_v, m_f, m_tu, m_tv, m_du;
    DeviceArray<std::uint32_t> m_hold;
    bool m_central;
    StepArrays<T> m_d;
    ElementParams<Law, T> m_p;
    using ElementKernel = void (*)(StepArrays<T>, ElementParams<Law, T>);
    ElementKernel m_tetKernel = tetKernel<Law, T>, m_hexKernel = hexKernel<Law, T>;  ///< the relaxed ones with Prony series
};

} // namespace

std::unique_ptr<StepRunner> makeCudaRunner(const StepSetup& s, Precision p, int block) {
    return selectDeviceLaw(s.material, [&](auto tag, const materials::BaseMaterial* m) -> std::unique_ptr<StepRunner> {
        using Law = typename decltype(tag)::type;
        if constexpr (std::is_same_v<Law, elements::GenericLaw>) {
            m->fail("the material " + m->className() + " is not on the GPU step (it runs " + deviceLawNames() + ")");
        } else {
            const Law& law = elements::lawOf<Law>(m);
            if (p == Precision::Float) return std::make_unique<CudaRunner<Law, float>>(s, law, block);
            return std::make_unique<CudaRunner<Law, double>>(s, law, block);
        }
    });
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
