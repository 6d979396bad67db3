#pragma once
/// A material of a user's own: written once against the shared invariant-based interface, it runs
/// in HEMLForceField and TLEDForceField alike, without touching either.
#include "fascia/materials/Laws.h"

namespace example {

/// The isochoric part of Yeoh's law, C10 x + C20 x^2 + C30 x^3 with x = I1bar - 3, composed with
/// the volumetric part kappa/2 (J - 1)^2 that Fascia provides (fascia/materials/Volumetric.h).
/// Written the documented way (docs/design.md, "how to add a law"): isochoric() templated on the
/// scalar T, parameters stored as double and converted to T once per call, constants written
/// T(...), so that the same law runs in double and in float (and, FASCIA_HD, in CUDA device code);
/// its W as text in kEnergy, from which the registry's description is built.
struct YeohIso {
    static constexpr unsigned uses = 0;
    static constexpr const char* kEnergy = "C10 (I1bar - 3) + C20 (I1bar - 3)^2 + C30 (I1bar - 3)^3";
    static constexpr bool kStressFreeAtRest = true;
    double C10 = 0, C20 = 0, C30 = 0;
    template <class T>
    FASCIA_HD void isochoric(const fascia::materials::InvariantsT<T>& in, fascia::materials::ResponseT<T>& r) const {
        const T C10 = T(this->C10), C20 = T(this->C20), C30 = T(this->C30);
        const T t = fascia::materials::invCbrt(in.J), t2 = t * t;  // J^(-1/3), J^(-2/3)
        const T x = in.I1 * t2 - T(3);
        const T dWdI1bar = C10 + x * (T(2) * C20 + T(3) * C30 * x);
        r.W += x * (C10 + x * (C20 + C30 * x));
        r.dI1 += dWdI1bar * t2;
        r.dJiso += dWdI1bar * in.I1 * T(-2.0 / 3.0) * t2 * t2 * t;  // d(I1 J^-2/3)/dJ = -2/3 I1 J^-5/3
    }
};
using YeohLaw = fascia::materials::ComposedLaw<YeohIso, fascia::materials::QuadraticVolume>;

class Yeoh : public fascia::materials::Material<YeohLaw> {
public:
    static constexpr const char* kTitle = "Yeoh (example plugin)";
    static constexpr const char* kTerms = "I1bar = J^(-2/3) tr C, C = F^T F, J = det F; shear modulus 2 C10, bulk modulus kappa";
    void init() override;
    double shearModulus() const override { return 2 * m_law.C10; }
    double bulkModulus() const override { return m_law.kappa; }

    fascia::core::Param<double> m_C10{this, fascia::core::ParamSpec("C10").unit("Pa").above(0).required().help("first coefficient (initial shear modulus / 2)")};
    fascia::core::Param<double> m_C20{this, fascia::core::ParamSpec("C20").unit("Pa").help("second coefficient"), 0.0};
    fascia::core::Param<double> m_C30{this, fascia::core::ParamSpec("C30").unit("Pa").help("third coefficient"), 0.0};
    fascia::core::Param<double> m_kappa{this, fascia::core::ParamSpec("kappa").unit("Pa").above(0).required().help("bulk modulus of kappa/2 (J - 1)^2")};
};

} // namespace example
