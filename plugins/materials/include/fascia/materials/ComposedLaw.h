#pragma once
/// A law as an isochoric part plus a volumetric part (docs/design.md, section 4.1).
///
/// The isochoric part is a struct with everything of W but its pure-J part:
///   static constexpr unsigned uses;              // BaseMaterial::UsesI2 | UsesI4 | UsesI6 it reads
///   static constexpr const char* kEnergy;        // its W as text, e.g. "mu/2 (I1bar - 3)"
///   static constexpr bool kStressFreeAtRest;     // its rest stress is zero
///   double ...;                                  // its parameters (Pa), filled by the component
///   template <class T> FASCIA_HD void isochoric(const InvariantsT<T>&, ResponseT<T>&) const;
///       // adds W and its first derivatives dI1, dI2, dI4, dI6, dJiso (Material.h); J > 0
/// and the volumetric part is one of Volumetric.h (NoVolume, QuadraticVolume, LogVolume,
/// HemlLogVolume) or one of the same shape. ComposedLaw<Iso, Vol> is then the law struct every
/// force field inlines (Material.h): it has both parts' parameters as its own members
/// (law.mu, law.kappa), and its energy as text is the two parts' texts joined, which the
/// registry's descriptions are built from (materialDescription), so W is written once per part.
/// The second derivatives an implicit solver needs go into the isochoric part beside the first
/// ones (the volumetric parts already give d2U/dJ2).
#include "fascia/materials/Material.h"
#include "fascia/materials/Volumetric.h"

#include <string>

namespace fascia::materials {

template <class Iso, class Vol>
struct ComposedLaw : Iso, Vol {
    using Isochoric = Iso;
    using Volumetric = Vol;
    static constexpr unsigned uses = Iso::uses;
    using Iso::isochoric;
    using Vol::volumetric;
    /// Both parts stress-free at rest. A law whose parts balance each other's rest stress (HEML
    /// eq. (26)) says so itself, by hiding this with its own test.
    bool stressFreeAtRest() const { return Iso::kStressFreeAtRest && Vol::kStressFreeAtRest; }

    /// W as text: "mu/2 (I1bar - 3) + kappa/2 (J - 1)^2".
    static std::string energy() {
        const std::string iso = Iso::kEnergy, vol = Vol::kEnergy;
        if (vol.empty()) return iso;
        if (vol[0] == '-') return iso + " - " + vol.substr(1);
        return iso + " + " + vol;
    }
};

/// The registry description of a material component M (derived from Material<ComposedLaw<...>>):
/// line 1, for --list: M::kTitle and W; line 2, for --describe: W in full with M::kTerms (the
/// invariants, parameter conversions and moduli) and the parts a ViscoelasticProny relaxes.
template <class M>
std::string materialDescription() {
    using Law = typename M::LawType;
    using Vol = typename Law::Volumetric;
    const std::string W = Law::energy(), vol = Vol::kEnergy;
    std::string parts = std::string("isochoric ") + Law::Isochoric::kEnergy + ", " +
                        (vol.empty() ? std::string("no volumetric part") : "volumetric " + vol);
    if (!Law::Isochoric::kStressFreeAtRest)
        parts += " (with s ln J moved from the first to the second so that the isochoric part is stress-free at rest: "
                 "docs/materials.md, section 3)";
    return std::string(M::kTitle) + ": " + W + "\nW = " + W + ", " + M::kTerms + "; ViscoelasticProny parts: " + parts;
}

} // namespace fascia::materials
