// Compile-only check that every built-in law, the example plugin's user law and the libm-free
// functions compile as CUDA device code, in float and in double (fascia/base/Hd.h): nvcc refuses a
// call from a __host__ __device__ function to a host-only one (error 20014 with -Werror
// all-warnings), so a law or helper that lacks FASCIA_HD, or calls what device code lacks, fails
// here. Registered as the test materials_device_compile where nvcc is found
// (plugins/materials/CMakeLists.txt); nothing is run, so no GPU is needed.
#include "Yeoh.h"
#include "fascia/materials/BuiltinMaterials.h"

namespace {

using namespace fascia::materials;

template <class Law, class T>
__global__ void evaluateKernel(Law law, const InvariantsT<T>* in, ResponseT<T>* out, int n, double J0) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) evaluateLaw(law, in[i], J0, out[i]);
}

template <class T>
__global__ void functionsKernel(const T* x, T* y, int n) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) y[i] = invCbrt(x[i]) + fastLog(x[i]) + fastExp(x[i]) + fastExprel(x[i]);
}

template <class T, class... Ms>
void launchAll(MaterialList<Ms...>) {
    (evaluateKernel<typename Ms::LawType, T><<<1, 1>>>(typename Ms::LawType{}, nullptr, nullptr, 0, 0.25), ...);
    evaluateKernel<example::YeohLaw, T><<<1, 1>>>(example::YeohLaw{}, nullptr, nullptr, 0, 0.25);
    functionsKernel<T><<<1, 1>>>(nullptr, nullptr, 0);
}

} // namespace

void lawsOnDevice() {
    launchAll<float>(BuiltinMaterials{});
    launchAll<double>(BuiltinMaterials{});
}
