#pragma once
/// Invariant-based hyperelastic laws, shared by HEMLForceField and TLEDForceField
/// (docs/design.md, the element layer): a law gives W and its derivatives w.r.t. the invariants of
/// C = F^T F; TLED turns them into S = 2 dW/dC, HEML into dW/dl (squared edge lengths).
/// A law written once (in this plugin or in a user's plugin) runs in both force fields.
///
/// The law interface is templated on the scalar type T (double on the CPU today; float for the
/// mixed-precision and GPU element kernels), and marked FASCIA_HD (fascia/base/Hd.h) so that the
/// same code compiles for CUDA device code. New code spells the types InvariantsT<T> and
/// ResponseT<T>; Invariants and Response are their double instances, kept so that existing code and
/// user plugins (BaseMaterial::evaluate, laws written for double only) compile unchanged.
#include "fascia/base/Component.h"
#include "fascia/base/Hd.h"

#include <algorithm>
#include <cstddef>

namespace fascia::materials {

/// Invariants of the right Cauchy-Green tensor C of one element, in the scalar type T.
template <class T>
struct InvariantsT {
    T I1 = 3;  ///< tr C
    T I2 = 3;  ///< (I1^2 - tr(C^2)) / 2
    T J = 1;   ///< det F, signed (negative for an inverted element)
    T I4 = 1;  ///< a0 . C a0 (first fibre direction), 1 when unused
    T I6 = 1;  ///< b0 . C b0 (second fibre direction), 1 when unused
};
/// The double invariants (BaseMaterial::evaluate, the conformance harness, laws written for double).
using Invariants = InvariantsT<double>;

/// Energy density (J/m^3 of reference volume) and its partial derivatives w.r.t. the invariants,
/// in the scalar type T.
/// The derivatives are partial derivatives of W(I1, I2, J, I4, I6) w.r.t. the plain (not the
/// modified, "bar") invariants, each taken with the others held fixed; laws written with modified
/// invariants (I1bar = J^(-2/3) I1 ...) put the chain-rule J terms into dJiso. Then
///   S = 2 dW/dC = 2 [dI1 I + dI2 (I1 I - C) + dI4 A0 + dI6 B0] + J (dJiso + dJvol) C^-1,
/// and at rest (C = I) S = 0 iff dI1 + 2 dI2 + (dJiso + dJvol)/2 = 0 and dI4 = dI6 = 0.
/// The J derivative is split into the part that comes through the isochoric (modified)
/// invariants and the volumetric part, so that viscoelasticity can act on either.
template <class T>
struct ResponseT {
    T W = 0;
    T dI1 = 0, dI2 = 0, dI4 = 0, dI6 = 0;
    T dJiso = 0;  ///< dW/dJ through the isochoric part (0 for laws without a split)
    T dJvol = 0;  ///< dW_vol/dJ
};
/// The double response (BaseMaterial::evaluate, the conformance harness, laws written for double).
using Response = ResponseT<double>;

/// A law as a plain struct (the fast, inlinable form used by built-in materials, see Laws.h):
///   static constexpr unsigned uses;                  // bit set of BaseMaterial::Uses
///   bool stressFreeAtRest() const;                   // S = 0 at C = I
///   template <class T> FASCIA_HD void isochoric(const InvariantsT<T>&, ResponseT<T>&) const;
///       // everything but the pure-J part; adds to W, dI1, dI2, dI4, dI6, dJiso; called with J > 0
///   template <class T> FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const;  // pure-J part, J > 0
/// Its parameters are double members, converted to T once at the top of each call
/// (`const T mu = T(this->mu);`), and its constants are written T(0.5), T(2.0 / 3.0), so that a
/// float instance computes in float throughout and the double instance is the double code.
/// A law written for double only (isochoric(const Invariants&, Response&), volumetric(double,
/// double&, double&, double&), the form before the scalar template) still compiles and runs in
/// every double path; only the float paths need the template.
///
/// evaluateLaw applies the flat/inverted element treatment of HEML section 4.4: below J0 the
/// isochoric part is evaluated at J0 (its J derivative dropped) and the volumetric part continues
/// along its tangent at J0 (W extended by its second-order Taylor polynomial), through J = 0 and
/// into inversion. The result is still the exact gradient of an energy, so crushed elements
/// push back with finite forces and no NaN appears. (Continuous energy; for split laws the
/// isochoric J derivative jumps at J0, so check gradients away from J0.) J0 is given in double and
/// converted to T once.
template <class Law, class T>
FASCIA_HD inline void evaluateLaw(const Law& law, const InvariantsT<T>& in, double J0, ResponseT<T>& r) {
    // written with min/max and one select, no branches, so that element loops vectorise
    const T j0 = T(J0);
    r = ResponseT<T>{};
    InvariantsT<T> c = in;
    c.J = std::max(in.J, j0);
    const T d = std::min(in.J - j0, T(0));  // < 0 only below J0
    law.isochoric(c, r);
    r.dJiso = d < T(0) ? T(0) : r.dJiso;
    T W, dW, d2W;
    law.volumetric(c.J, W, dW, d2W);
    r.W += W + (dW + T(0.5) * d2W * d) * d;
    r.dJvol = dW + d2W * d;
}

/// A material: a component placed in the force field's node (or linked by material="@name").
class BaseMaterial : public core::Component {
public:
    enum Uses : unsigned { UsesI2 = 1u, UsesI4 = 2u, UsesI6 = 4u };
    /// Which optional invariants the law reads (the force field skips the others).
    virtual unsigned uses() const = 0;
    /// Evaluates n elements: one virtual call per block of elements, never per element.
    virtual void evaluate(const Invariants* in, Response* out, size_t n, double J0) const = 0;
    /// Small-strain moduli at rest (Pa), for wave speeds and stable time steps.
    virtual double shearModulus() const = 0;
    virtual double bulkModulus() const = 0;
    /// Dilatational wave speed sqrt((kappa + 4/3 mu)/rho) in m/s (rho in kg/m^3). Anisotropic
    /// materials override it with an upper bound that includes their fibre stiffness.
    virtual double waveSpeed(double rho) const;
    /// Fibre direction a0 (which = 0) or b0 (which = 1) of anisotropic materials, unit length;
    /// null for isotropic ones. Force fields use it where the mesh gives no per-element direction.
    virtual const Vec3* fibreDirection(int which) const { return nullptr; }
    /// True when the law gives S = 0 at C = I (see Response). False for the HEML paper's
    /// "incompressible" laws, which have no pressure term (Table 3). Default: true.
    virtual bool stressFreeAtRest() const { return true; }
};

/// Adapts a law struct to BaseMaterial. Force fields may dynamic_cast to Material<Law> and
/// call law() to run a fully inlined element loop for the built-in laws.
template <class Law>
class Material : public BaseMaterial {
public:
    using LawType = Law;
    unsigned uses() const override { return Law::uses; }
    bool stressFreeAtRest() const override { return m_law.stressFreeAtRest(); }
    void evaluate(const Invariants* in, Response* out, size_t n, double J0) const override {
        for (size_t i = 0; i < n; ++i) evaluateLaw(m_law, in[i], J0, out[i]);
    }
    const Law& law() const { return m_law; }

protected:
    Law m_law{};
};

} // namespace fascia::materials
