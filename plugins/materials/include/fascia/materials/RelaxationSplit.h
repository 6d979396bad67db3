#pragma once
/// What a viscoelastic relaxation of one part of a law acts on (ViscoelasticProny apply="isochoric",
/// "volumetric" or "both", in HEMLForceField and TLEDForceField).
///
/// A Prony series relaxes the response of the part it is applied to (TLED eq. (24), HEML eq. (18)).
/// If that part carries a stress at rest, balanced at rest by the other part, relaxation undoes the
/// balance and a body at rest creeps by itself. CompressibleNeoHookean is the case in point: its
/// isochoric() part C1 (I1 - 3) has the rest stress 2 C1 I, which the -mu ln J of its volumetric()
/// part balances (HEML eq. (26)).
///
/// The relaxed parts are therefore the law's isochoric and volumetric parts with s ln J moved from
/// the first to the second, s chosen so that the isochoric part is stress-free at rest:
///   W_iso' = W_iso - s ln J,  W_vol' = W_vol + s ln J,  s = 2 (dI1 + 2 dI2) + dJiso at C = I
/// (S of s ln J is s C^-1, which is s I at rest; see Response for S at rest). W_iso' + W_vol' = W, so
/// the elastic response is unchanged. For CompressibleNeoHookean s = 2 C1 and the parts become
/// C1 (I1 - 3) - 2 C1 ln J and lambda/2 (ln J)^2 - (mu - 2 C1) ln J: with C1 = mu/2 the grouping
/// mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2 of HEML eq. (26) into its shear and bulk terms. For
/// laws written with the modified invariants (NeoHookean, Mooney-Rivlin, the fibre laws, Arruda-Boyce)
/// and for StVenantKirchhoff s = 0: their isochoric parts are stress-free at rest already.
///
/// After the shift the isochoric part is stress-free at rest unless the law's rest stress has an
/// anisotropic part (dI4 or dI6 non-zero at C = I, which a J term cannot cancel), and the volumetric
/// part is stress-free at rest iff the whole law is. A relaxation of a part that is not stress-free at
/// rest is an input error (relaxationRestError): for the HEML paper's "incompressible" laws and for
/// CompressibleNeoHookean with C1 != mu/2 only apply="isochoric" is valid.
#include "fascia/materials/Material.h"

#include <cmath>
#include <string>

namespace fascia::materials {

/// The rest split of one material (computed once, at the force field's init).
struct RelaxationSplit {
    /// s of the s ln J moved from the isochoric to the volumetric part (Pa): in a relaxed element
    /// dJiso' = dJiso - s / J and dJvol' = dJvol + s / J. Exactly 0 where the isochoric part is
    /// stress-free at rest to round-off (so that those laws' relaxed results do not change).
    double shift = 0;
    bool isochoricAtRest = true;   ///< W_iso' is stress-free at rest (relaxing it alone is valid)
    bool volumetricAtRest = true;  ///< W_vol' is stress-free at rest (relaxing it alone is valid)
    bool lawAtRest = true;         ///< W is stress-free at rest (relaxing both parts is valid)
};

/// Evaluates the material once at rest (C = I) and returns its split. Rest stresses below
/// 1e-12 (shear + bulk modulus) count as round-off, and so does an s below 1e-12 of the terms it
/// sums.
inline RelaxationSplit relaxationSplit(const BaseMaterial& m, double J0) {
    Invariants rest;
    Response r;
    m.evaluate(&rest, &r, 1, J0);
    const double scale = std::abs(m.shearModulus()) + std::abs(m.bulkModulus());
    const double tol = 1e-12 * (scale > 0 ? scale : 1.0);
    RelaxationSplit out;
    // the isotropic rest stress of the isochoric part, s I (Response: S at C = I)
    const double s = 2.0 * (r.dI1 + 2.0 * r.dI2) + r.dJiso;
    const double aniso = 2.0 * (std::abs(r.dI4) + std::abs(r.dI6));
    const double sScale = std::abs(2.0 * r.dI1) + std::abs(4.0 * r.dI2) + std::abs(r.dJiso);
    out.shift = std::abs(s) <= 1e-12 * sScale ? 0.0 : s;
    out.isochoricAtRest = aniso <= tol;
    out.volumetricAtRest = std::abs(r.dJvol + out.shift) <= tol;
    out.lawAtRest = m.stressFreeAtRest() && aniso <= tol && std::abs(s + r.dJvol) <= tol;
    return out;
}

/// Empty when relaxing the given parts (iso: the isochoric part, vol: the volumetric part, both:
/// their sum) of a material with this split leaves a body at rest at rest; otherwise the reason and
/// the valid `apply` values, for an input error located at the ViscoelasticProny. `law` names the
/// material ("CompressibleNeoHookean 'mat'").
inline std::string relaxationRestError(const RelaxationSplit& sp, bool iso, bool vol, const std::string& law) {
    const bool ok = iso && vol ? sp.lawAtRest : iso ? sp.isochoricAtRest : vol ? sp.volumetricAtRest : true;
    if (ok) return {};
    std::string valid;
    const auto add = [&](const char* v) { valid += (valid.empty() ? "" : " or ") + std::string("apply=\"") + v + "\""; };
    if (sp.isochoricAtRest) add("isochoric");
    if (sp.volumetricAtRest) add("volumetric");
    if (sp.lawAtRest) add("both");
    const char* part = iso && vol ? "the whole response" : iso ? "the isochoric part" : "the volumetric part";
    std::string msg = std::string("apply=\"") + (iso && vol ? "both" : iso ? "isochoric" : "volumetric") +
                      "\" relaxes " + part + " of " + law + ", which carries a stress at rest (" +
                      (iso && vol ? "the law is not stress-free at rest" : "balanced by the other part") +
                      "): relaxing it would make a body at rest creep by itself; ";
    msg += valid.empty() ? "no apply value is valid for this law (its rest stress is anisotropic): remove the "
                           "ViscoelasticProny or use a law that is stress-free at rest"
                         : "valid for this law: " + valid;
    return msg;
}

} // namespace fascia::materials
