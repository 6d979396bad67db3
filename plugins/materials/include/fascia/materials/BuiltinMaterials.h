#pragma once
/// The one list of built-in materials. Each entry is a component class derived from Material<Law>,
/// Law a ComposedLaw (ComposedLaw.h), with `static constexpr const char* kName`, `kTitle` (the
/// law's name and source), `kTerms` (its invariants, parameter conversions and moduli) and
/// `kExample`; the list drives:
///   - the registration of the materials plugin (MaterialsPlugin.cpp: --list, --describe, with the
///     description built by materialDescription from the law's parts);
///   - the scene dump (tests/regression/SceneDump.cpp), the fuzz dictionary check and the
///     materials doc checks (a section per law, with the energy the code computes:
///     plugins/materials/tests/TestLawLists.cpp);
///   - the inlined element loops of HEMLForceField and TLEDForceField (fascia/elements/LawDispatch.h);
///   - the test factories and conformance sweeps (createBuiltinMaterial, forEachBuiltinMaterial).
/// Adding a built-in law: one header with its law struct and component (see docs/design.md, "how to
/// add a law"), and one entry here.
#include "fascia/materials/ArrudaBoyce.h"
#include "fascia/materials/CompressibleMooneyRivlin.h"
#include "fascia/materials/CompressibleNeoHookean.h"
#include "fascia/materials/Gent.h"
#include "fascia/materials/HolzapfelGasserOgden.h"
#include "fascia/materials/IncompressibleMooneyRivlin.h"
#include "fascia/materials/IncompressibleNeoHookean.h"
#include "fascia/materials/NeoHookean.h"
#include "fascia/materials/Orthotropic.h"
#include "fascia/materials/StVenantKirchhoff.h"
#include "fascia/materials/TransverselyIsotropic.h"
#include "fascia/materials/UncoupledMooneyRivlin.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace fascia::materials {

/// A compile-time list of material component classes (each with kName, kTitle, kTerms and kExample).
template <class... Ms>
struct MaterialList {
    static constexpr size_t size = sizeof...(Ms);
};

using BuiltinMaterials = MaterialList<StVenantKirchhoff, IncompressibleNeoHookean, IncompressibleMooneyRivlin,
                                      CompressibleNeoHookean, CompressibleMooneyRivlin, NeoHookean,
                                      TransverselyIsotropic, Orthotropic, HolzapfelGasserOgden, ArrudaBoyce,
                                      UncoupledMooneyRivlin, Gent>;

namespace detail {
template <class F, class... Ms>
void forEachIn(F&& f, MaterialList<Ms...>) {
    (f(static_cast<Ms*>(nullptr)), ...);
}
} // namespace detail

/// Calls f(static_cast<M*>(nullptr)) for every built-in material class M, in list order.
template <class F>
void forEachBuiltinMaterial(F&& f) {
    detail::forEachIn(f, BuiltinMaterials{});
}

/// The class names of the built-in materials, in list order.
inline std::vector<std::string> builtinMaterialNames() {
    std::vector<std::string> out;
    forEachBuiltinMaterial([&](auto* tag) { out.push_back(std::decay_t<decltype(*tag)>::kName); });
    return out;
}

/// A new, uninitialised built-in material by class name; null for an unknown name.
inline std::unique_ptr<BaseMaterial> createBuiltinMaterial(const std::string& className) {
    std::unique_ptr<BaseMaterial> out;
    forEachBuiltinMaterial([&](auto* tag) {
        using M = std::decay_t<decltype(*tag)>;
        if (!out && className == M::kName) out = std::make_unique<M>();
    });
    return out;
}

/// The example parameters (M::kExample) of a built-in material as (name, value) pairs; empty for an
/// unknown name.
inline std::vector<std::pair<std::string, std::string>> exampleParameters(const std::string& className) {
    std::vector<std::pair<std::string, std::string>> out;
    forEachBuiltinMaterial([&](auto* tag) {
        using M = std::decay_t<decltype(*tag)>;
        if (className != M::kName) return;
        const std::string text = M::kExample;
        for (size_t a = 0; a < text.size();) {
            size_t b = text.find(';', a);
            if (b == std::string::npos) b = text.size();
            const std::string item = text.substr(a, b - a);
            const size_t eq = item.find('=');
            out.emplace_back(item.substr(0, eq), item.substr(eq + 1));
            a = b + 1;
        }
    });
    return out;
}

} // namespace fascia::materials
