#pragma once
/// Helpers shared by the element loops of the force fields (HEML, TLED and plugins): 64-byte
/// aligned storage, and the move of node data between node rows (4 doubles per node, the 4th is
/// padding) and structure-of-arrays batches of elements with in-register transposes
/// (hardware gathers and masked scatters are slower here: docs/performance.md, lesson 2).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <vector>
#if defined(__linux__)
#include <sys/mman.h>
#endif
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace fascia::simd {

#if defined(__linux__) && defined(MADV_HUGEPAGE)
#define FASCIA_HUGE_PAGES 1
/// Arrays of this size and more (streamed once per step on large meshes) are mapped on their own,
/// 2 MiB aligned, and marked for transparent huge pages (fewer TLB misses; docs/performance.md).
constexpr size_t kHugeArray = size_t(4) << 20, kHugePage = size_t(2) << 20;
/// bytes (a multiple of kHugePage) of fresh zeroed memory aligned to kHugePage, or null.
inline void* mapHuge(size_t bytes) {
    void* raw = mmap(nullptr, bytes + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) return nullptr;
    char* r = static_cast<char*>(raw);
    char* p = reinterpret_cast<char*>((reinterpret_cast<uintptr_t>(r) + kHugePage - 1) & ~(uintptr_t(kHugePage) - 1));
    if (p > r) munmap(r, static_cast<size_t>(p - r));             // the head before the alignment
    munmap(p + bytes, static_cast<size_t>(r + kHugePage - p));     // the tail after the array (never empty)
    madvise(p, bytes, MADV_HUGEPAGE);  // advice only: without transparent huge pages it stays 4 KiB pages
    return p;
}
#endif

/// 64-byte aligned storage for element and node arrays (large ones in 2 MiB pages on Linux).
template <class T>
struct AlignedAllocator {
    using value_type = T;
    AlignedAllocator() = default;
    template <class U> AlignedAllocator(const AlignedAllocator<U>&) {}
    static size_t bytesFor(size_t n) {
        if (n > (~size_t(0) - 64) / sizeof(T)) throw std::bad_array_new_length();
        const size_t bytes = ((n * sizeof(T) + 63) / 64) * 64;
#ifdef FASCIA_HUGE_PAGES
        if (bytes >= kHugeArray) return (bytes + kHugePage - 1) / kHugePage * kHugePage;
#endif
        return bytes ? bytes : 64;
    }
    T* allocate(size_t n) {
        const size_t bytes = bytesFor(n);
        void* p = nullptr;
#ifdef FASCIA_HUGE_PAGES
        if (bytes >= kHugeArray) p = mapHuge(bytes);
        else
#endif
            p = std::aligned_alloc(64, bytes);
        if (!p) throw std::bad_alloc();
        return static_cast<T*>(p);
    }
    void deallocate(T* p, size_t n) {
        const size_t bytes = bytesFor(n);
#ifdef FASCIA_HUGE_PAGES
        if (bytes >= kHugeArray) {
            munmap(p, bytes);
            return;
        }
#endif
        (void)bytes;
        std::free(p);
    }
    template <class U> bool operator==(const AlignedAllocator<U>&) const { return true; }
    template <class U> bool operator!=(const AlignedAllocator<U>&) const { return false; }
};
using DVec = std::vector<double, AlignedAllocator<double>>;
using IVec = std::vector<int, AlignedAllocator<int>>;

#if defined(__AVX__)
/// 4x4 transpose of doubles: rows r0..r3 become columns.
inline void transpose4(__m256d& r0, __m256d& r1, __m256d& r2, __m256d& r3) {
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
    const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
    r0 = _mm256_permute2f128_pd(t0, t2, 0x20);
    r1 = _mm256_permute2f128_pd(t1, t3, 0x20);
    r2 = _mm256_permute2f128_pd(t0, t2, 0x31);
    r3 = _mm256_permute2f128_pd(t1, t3, 0x31);
}
#endif

/// Four elements' node rows into structure of arrays: rows[4 idx[i * stride]] (x y z pad) of element
/// i = 0..3 go to x[i], y[i], z[i]. x, y and z must be 32-byte aligned.
inline void gather4(const double* rows, const int* idx, size_t stride, double* x, double* y, double* z) {
#if defined(__AVX__)
    __m256d r0 = _mm256_loadu_pd(rows + 4 * size_t(idx[0]));
    __m256d r1 = _mm256_loadu_pd(rows + 4 * size_t(idx[stride]));
    __m256d r2 = _mm256_loadu_pd(rows + 4 * size_t(idx[2 * stride]));
    __m256d r3 = _mm256_loadu_pd(rows + 4 * size_t(idx[3 * stride]));
    transpose4(r0, r1, r2, r3);
    _mm256_store_pd(x, r0);
    _mm256_store_pd(y, r1);
    _mm256_store_pd(z, r2);
#else
    for (size_t i = 0; i < 4; ++i) {
        const double* p = rows + 4 * size_t(idx[i * stride]);
        x[i] = p[0];
        y[i] = p[1];
        z[i] = p[2];
    }
#endif
}

/// The reverse, adding: rows[4 (idx[i * stride] - base)] += (x[i], y[i], z[i]) for i = 0..3 in that
/// order (each row is loaded, added and stored before the next, so elements sharing a node add up
/// correctly and always in the same order). x, y and z must be 32-byte aligned.
inline void scatterAdd4(double* rows, const int* idx, size_t stride, const double* x, const double* y, const double* z,
                        int base = 0) {
#if defined(__AVX__)
    __m256d r0 = _mm256_load_pd(x);
    __m256d r1 = _mm256_load_pd(y);
    __m256d r2 = _mm256_load_pd(z);
    __m256d r3 = _mm256_setzero_pd();
    transpose4(r0, r1, r2, r3);
    double* p0 = rows + 4 * size_t(idx[0] - base);
    _mm256_storeu_pd(p0, _mm256_add_pd(_mm256_loadu_pd(p0), r0));
    double* p1 = rows + 4 * size_t(idx[stride] - base);
    _mm256_storeu_pd(p1, _mm256_add_pd(_mm256_loadu_pd(p1), r1));
    double* p2 = rows + 4 * size_t(idx[2 * stride] - base);
    _mm256_storeu_pd(p2, _mm256_add_pd(_mm256_loadu_pd(p2), r2));
    double* p3 = rows + 4 * size_t(idx[3 * stride] - base);
    _mm256_storeu_pd(p3, _mm256_add_pd(_mm256_loadu_pd(p3), r3));
#else
    for (size_t i = 0; i < 4; ++i) {
        double* p = rows + 4 * size_t(idx[i * stride] - base);
        p[0] += x[i];
        p[1] += y[i];
        p[2] += z[i];
    }
#endif
}

/// dst[0..n) = src[0..n) with non-temporal (streaming) stores where the CPU has them: for large
/// arrays written now and read next step, this avoids reading dst into the cache first and keeps
/// it from evicting data that stays hot. dst and src 64-byte aligned, n a multiple of 8. Call
/// streamFence() before another thread reads dst.
inline void streamCopy(double* dst, const double* src, size_t n) {
#if defined(__AVX512F__)
    for (size_t i = 0; i < n; i += 8) _mm512_stream_pd(dst + i, _mm512_load_pd(src + i));
#elif defined(__AVX__)
    for (size_t i = 0; i < n; i += 4) _mm256_stream_pd(dst + i, _mm256_load_pd(src + i));
#else
    for (size_t i = 0; i < n; ++i) dst[i] = src[i];
#endif
}
/// Prefetches [p, p + bytes) into the cache (a hint). On x86-64 with GCC or clang, as volatile
/// asm: GCC 12 deletes a loop whose only statements are __builtin_prefetch calls as a loop without
/// side effects once it is inlined into a large caller, and so dropped every prefetch of TLED's
/// element loop (docs/performance.md, lesson 11).
inline void prefetch(const void* p, size_t bytes) {
    const char* c = static_cast<const char*>(p);
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    for (size_t i = 0; i < bytes; i += 64) __asm__ volatile("prefetcht0 %0" : : "m"(c[i]));
#else
    for (size_t i = 0; i < bytes; i += 64) __builtin_prefetch(c + i, 0, 3);
#endif
}
inline void streamFence() {
#if defined(__AVX__)
    _mm_sfence();
#endif
}

} // namespace fascia::simd
