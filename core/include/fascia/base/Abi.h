#pragma once
/// The binary interface between libfascia_core, its plugins and the programs that link it, in the
/// respects that compile flags change (docs/design.md, section 2, "One ABI").
///
/// Eigen's alignment follows the instruction set: by default EIGEN_MAX_ALIGN_BYTES is 16 with SSE,
/// 32 with AVX and 64 with AVX-512, and with it the size, alignment and padding of Eigen's fixed
/// vectorisable types (Quaterniond, Isometry3d, Vector2d, Matrix4d...) and of every struct that
/// holds one. The library is built with -march=native; a program built for another machine
/// (-march=x86-64) would see the same struct with another layout and crash or read garbage.
/// Fascia fixes the bound at 16 bytes everywhere instead (Eigen supports a bound below the packet
/// size for exactly this: it then uses unaligned loads), so that a consumer built with any flags
/// agrees with the library. The CMake package and the pkg-config file pass the definition; this
/// header sets it when it comes first and refuses, at compile time, a translation unit that sees
/// Eigen with another bound (one that included Eigen first, or defined its own value).
#define FASCIA_EIGEN_MAX_ALIGN_BYTES 16
#ifndef EIGEN_MAX_ALIGN_BYTES
#define EIGEN_MAX_ALIGN_BYTES FASCIA_EIGEN_MAX_ALIGN_BYTES
#endif

// The debug mode of libstdc++ changes the layout of std::vector, std::string and the other
// containers that the public types hold; the library is built without it.
#if defined(_GLIBCXX_DEBUG)
#error "Fascia: this translation unit is compiled with _GLIBCXX_DEBUG, which changes the layout of the std containers in Fascia's public types; libfascia_core is built without it: compile without _GLIBCXX_DEBUG (_GLIBCXX_ASSERTIONS is fine)"
#endif

#include <Eigen/Core>

namespace fascia::core {

/// Instantiated with the bounds this translation unit sees: a mismatch stops the compile with the
/// values in the compiler's message ("in instantiation of EigenAlignmentCheck<64, 64>"). The static
/// bound must be 16 too: EIGEN_DONT_VECTORIZE or EIGEN_DONT_ALIGN_STATICALLY make it 0, and then
/// a Quaterniond is 8-byte aligned and core::Pose 56 bytes instead of 64.
template <int SeenMaxAlignBytes, int SeenMaxStaticAlignBytes>
struct EigenAlignmentCheck {
    static_assert(SeenMaxAlignBytes == FASCIA_EIGEN_MAX_ALIGN_BYTES && SeenMaxStaticAlignBytes == FASCIA_EIGEN_MAX_ALIGN_BYTES,
                  "Fascia: this translation unit sees Eigen with another EIGEN_MAX_ALIGN_BYTES (or "
                  "EIGEN_MAX_STATIC_ALIGN_BYTES, e.g. through EIGEN_DONT_VECTORIZE) than libfascia_core was built with (16, "
                  "FASCIA_EIGEN_MAX_ALIGN_BYTES): Eigen types would have another layout on the two sides "
                  "of the library. Link Fascia::fascia_core (CMake) or use `pkg-config --cflags fascia`, "
                  "which define EIGEN_MAX_ALIGN_BYTES=16, and define no other value yourself "
                  "(the values this unit sees are the template arguments of this instantiation)");
    static constexpr bool ok = true;
};
static_assert(EigenAlignmentCheck<EIGEN_MAX_ALIGN_BYTES, EIGEN_MAX_STATIC_ALIGN_BYTES>::ok);

/// How a translation unit was compiled, in the respects that the plugin loader compares with the
/// core (core/src/PluginManager.cpp): a plugin's is recorded in its PluginInfo by FASCIA_PLUGIN.
struct BuildAbi {
    int eigenMaxAlignBytes;        ///< EIGEN_MAX_ALIGN_BYTES: another value is refused
    int eigenMaxStaticAlignBytes;  ///< EIGEN_MAX_STATIC_ALIGN_BYTES (fixed-size objects): the same
    int optimised;                 ///< 1 when built with optimisation (__OPTIMIZE__): 0 is warned about
};

#if defined(__OPTIMIZE__)
#define FASCIA_BUILD_OPTIMISED 1
#else
#define FASCIA_BUILD_OPTIMISED 0
#endif

/// This translation unit's BuildAbi.
#define FASCIA_THIS_BUILD_ABI \
    (::fascia::core::BuildAbi{EIGEN_MAX_ALIGN_BYTES, EIGEN_MAX_STATIC_ALIGN_BYTES, FASCIA_BUILD_OPTIMISED})

/// libfascia_core's own, as it was compiled.
BuildAbi coreBuildAbi();

} // namespace fascia::core
