#pragma once
/// Dispatch over the built-in laws, driven by the one list materials::BuiltinMaterials: a force
/// field asks once per material (at init) for the instantiation of its element loop, and gets the
/// inlined loop of a built-in law or its generic loop (one virtual evaluate() per batch).
///
///   auto fn = elements::selectForLaw(material, [](auto law) -> KernelFn {
///       using Law = typename decltype(law)::type;   // elements::GenericLaw for other materials
///       return &kernel<Law>;
///   });
#include "fascia/materials/BuiltinMaterials.h"

#include <type_traits>

namespace fascia::elements {

/// Tag of a law type for the selector's generic lambda.
template <class Law>
struct LawTag {
    using type = Law;
};
/// The law "type" of materials outside the list: evaluated through BaseMaterial::evaluate.
struct GenericLaw {};

namespace detail {
template <class F, class M, class... Ms>
auto select(const materials::BaseMaterial* m, F& f, materials::MaterialList<M, Ms...>) {
    using Law = typename M::LawType;
    if (dynamic_cast<const materials::Material<Law>*>(m)) return f(LawTag<Law>{});
    if constexpr (sizeof...(Ms) > 0) return select(m, f, materials::MaterialList<Ms...>{});
    else return f(LawTag<GenericLaw>{});
}
} // namespace detail

/// f(LawTag<Law>{}) for the built-in law of m (m is a materials::Material<Law>), else
/// f(LawTag<GenericLaw>{}). Every call must return the same type (e.g. a function pointer).
template <class F>
auto selectForLaw(const materials::BaseMaterial* m, F&& f) {
    return detail::select(m, f, materials::BuiltinMaterials{});
}

/// The law struct of a material known to be materials::Material<Law>.
template <class Law>
const Law& lawOf(const materials::BaseMaterial* m) {
    return static_cast<const materials::Material<Law>*>(m)->law();
}

/// True when m runs an inlined loop (its law is in the list).
inline bool isBuiltinLaw(const materials::BaseMaterial* m) {
    return selectForLaw(m, [](auto tag) { return !std::is_same_v<typename decltype(tag)::type, GenericLaw>; });
}

} // namespace fascia::elements
