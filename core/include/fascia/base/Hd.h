#pragma once
/// FASCIA_HD marks the functions that run per element or per node and must compile for the GPU
/// later as well as for the CPU: the laws (fascia/materials: Material.h, Laws.h, FastExp.h and the
/// per-law headers), the element layer's 3x3 vocabulary, geometry and stress (fascia/elements).
/// It expands to `__host__ __device__` under nvcc and to nothing otherwise, so that host code is
/// unchanged. FASCIA_INLINE forces inlining into the vectorised batch loops.
///
/// Rules for code under FASCIA_HD, as nvcc 13 checks them (plugins/materials/tests/LawsOnDevice.cu,
/// the test materials_device_compile where nvcc is found):
/// - every function it calls is FASCIA_HD too. nvcc only warns about a call to a host-only function
///   (warning 20014), so the cuda build must turn warnings into errors (-Werror all-warnings, with
///   -diag-suppress 20012 for Eigen's defaulted constructors);
/// - std::min and std::max are fine: they are constexpr, which device code may call with
///   --expt-relaxed-constexpr (the cuda build must pass it; without it they are error 20013);
///   std::memcpy of a scalar's bits and std::abs are fine as they are;
/// - no libm in the laws (std::exp, std::log, std::pow, std::cbrt): materials::invCbrt, fastLog,
///   fastExp and fastExprel replace them, on the CPU because they vectorise (docs/performance.md,
///   lesson 1), on the GPU because they are the same code in both places;
/// - no allocation, no exception, no virtual call.
/// It lives in the core because every layer that has per-element code (materials, elements,
/// viscoelastic) needs it and the core is the only thing they all include.
#if defined(__CUDACC__)
#define FASCIA_HD __host__ __device__
#define FASCIA_INLINE __forceinline__
#else
#define FASCIA_HD
#if defined(__GNUC__)
#define FASCIA_INLINE inline __attribute__((always_inline))
#else
#define FASCIA_INLINE inline
#endif
#endif
