#pragma once
/// The laws the device step runs, in one list: every built-in law (materials::BuiltinMaterials,
/// each tested in test_cuda_emulation against TLEDForceField and HEMLForceField). Each costs three
/// element kernels (TLED's tetrahedra and hexahedra, HEML's tetrahedra) per precision and variant
/// in the .cu file (elastic or relaxed, over the whole mesh or a group's list; for TLED, with fibres
/// per element for the laws that read one: nvcc time in every build). A material not in it (a user's law), for all elements or a group's, is a located
/// error naming it (CudaStep), never a host fallback.
#include "fascia/elements/LawDispatch.h"
#include "fascia/materials/BuiltinMaterials.h"

namespace fascia::cuda {

using DeviceMaterials = materials::BuiltinMaterials;

namespace detail {
template <class F, class M, class... Ms>
auto selectDevice(const materials::BaseMaterial* m, F& f, materials::MaterialList<M, Ms...>) {
    using Law = typename M::LawType;
    if (dynamic_cast<const materials::Material<Law>*>(m)) return f(elements::LawTag<Law>{}, m);
    if constexpr (sizeof...(Ms) > 0) return selectDevice(m, f, materials::MaterialList<Ms...>{});
    else return f(elements::LawTag<elements::GenericLaw>{}, m);
}
} // namespace detail

/// f(LawTag<Law>{}, m) for the law of m when it is in DeviceMaterials, else
/// f(LawTag<elements::GenericLaw>{}, m). Every call must return the same type.
template <class F>
auto selectDeviceLaw(const materials::BaseMaterial* m, F&& f) {
    return detail::selectDevice(m, f, DeviceMaterials{});
}

/// The class names of DeviceMaterials, "NeoHookean, CompressibleNeoHookean, ..." (for messages).
std::string deviceLawNames();

} // namespace fascia::cuda
