#pragma once
/// FASCIA_HD marks the functions that run per element or per node and must compile for the GPU
/// later as well as for the CPU: the laws (fascia/materials: Material.h, Laws.h, FastExp.h and the
/// per-law headers), the element layer's 3x3 vocabulary, geometry and stress (fascia/elements).
/// It expands to `__host__ __device__` under nvcc and to nothing otherwise, so that host code is
/// unchanged. FASCIA_INLINE forces inlining into the vectorised batch loops.
///
/// Rules for code under FASCIA_HD (device code has no libstdc++ behind it):
/// - no libm (std::sqrt, std::exp, std::log, std::pow, std::cbrt, std::abs): the laws use
///   materials::invCbrt, fastLog, fastExp, fastExprel, and comparisons instead of std::abs;
/// - std::min and std::max are fine: they are constexpr, which nvcc accepts in device code with
///   --expt-relaxed-constexpr (the cuda build must pass it); std::memcpy of a scalar's bits is
///   fine too (device code has memcpy);
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
