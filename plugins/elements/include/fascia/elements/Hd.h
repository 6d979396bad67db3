#pragma once
/// FASCIA_HD marks the element-level functions of the element layer (3x3 vocabulary, geometry,
/// stress): `__host__ __device__` under nvcc, so that a CUDA path can call the same code, and
/// nothing otherwise. FASCIA_INLINE forces inlining into the vectorised batch loops.
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
