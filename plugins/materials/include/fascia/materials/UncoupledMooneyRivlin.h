#pragma once
/// FEBio's uncoupled Mooney-Rivlin: the law struct (inlined by the force fields, see Material.h)
/// and its component.
#include "fascia/materials/Laws.h"

#include <sstream>

namespace fascia::materials {

/// The uncoupled Mooney-Rivlin material of FEBio (Maas, Ellis, Ateshian & Weiss 2012, J. Biomech.
/// Eng. 134; FEBio's uncoupled materials take the volumetric part U(J) = k/2 (ln J)^2):
///   W = c1 (I1bar - 3) + c2 (I2bar - 3) + k/2 (ln J)^2,   I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2.
/// It differs from CompressibleMooneyRivlinLaw only in the volumetric part ((ln J)^2 instead of
/// (J - 1)^2), which grows without bound as J -> 0. Derivatives (Material.h):
///   dI1 = c1 J^(-2/3), dI2 = c2 J^(-4/3), dJiso = -2/(3 J) (c1 I1bar + 2 c2 I2bar),
///   dW_vol/dJ = k ln J / J,  d2W_vol/dJ2 = k (1 - ln J) / J^2.
/// Stress-free at rest; small-strain shear modulus 2 (c1 + c2), bulk modulus k. No libm: invCbrt,
/// fastLog.
struct UncoupledMooneyRivlinLaw {
    static constexpr unsigned uses = BaseMaterial::UsesI2;
    double c1 = 0, c2 = 0;  ///< Pa
    double k = 0;           ///< bulk modulus (Pa)
    bool stressFreeAtRest() const { return true; }
    void isochoric(const Invariants& in, Response& r) const {
        const double t = invCbrt(in.J), t2 = t * t, t4 = t2 * t2, iJ = t2 * t;
        const double I1b = in.I1 * t2, I2b = in.I2 * t4;
        r.W += c1 * (I1b - 3.0) + c2 * (I2b - 3.0);
        r.dI1 += c1 * t2;
        r.dI2 += c2 * t4;
        r.dJiso += -(2.0 / 3.0) * (c1 * I1b + 2.0 * c2 * I2b) * iJ;
    }
    void volumetric(double J, double& W, double& dW, double& d2W) const {
        const double lnJ = fastLog(J), iJ = 1.0 / J;
        W = 0.5 * k * lnJ * lnJ;
        dW = k * lnJ * iJ;
        d2W = k * (1.0 - lnJ) * iJ * iJ;
    }
};

/// FEBio's uncoupled Mooney-Rivlin (see UncoupledMooneyRivlinLaw). The parameters are FEBio's, by
/// the same names: <material type="Mooney-Rivlin"> with <c1>, <c2>, <k> becomes
/// <UncoupledMooneyRivlin c1="..." c2="..." k="..."/> (FEBio's density goes to the mass). c2 may be
/// negative, but c1 + c2 (half the shear modulus) must be positive.
class UncoupledMooneyRivlin : public Material<UncoupledMooneyRivlinLaw> {
public:
    static constexpr const char* kName = "UncoupledMooneyRivlin";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "c1=400;c2=150;k=20000";
    static constexpr const char* kDescription =
        "FEBio's uncoupled Mooney-Rivlin c1 (I1bar - 3) + c2 (I2bar - 3) + k/2 (ln J)^2";
    /// the energy in full, for --describe (a second line of the registry description)
    static constexpr const char* kEnergy =
        "W = c1 (I1bar - 3) + c2 (I2bar - 3) + k/2 (ln J)^2, I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2, I1 = tr C, I2 = (I1^2 - tr(C^2))/2, C = F^T F, J = det F (FEBio's uncoupled Mooney-Rivlin); shear modulus 2 (c1 + c2), bulk modulus k; ViscoelasticProny parts: isochoric c1 (I1bar - 3) + c2 (I2bar - 3), volumetric k/2 (ln J)^2";
    void init() override {
        m_law.c1 = m_c1.get();
        m_law.c2 = m_c2.get();
        m_law.k = m_k.get();
        if (!(m_law.c1 + m_law.c2 > 0)) {
            std::ostringstream os;
            os << "c1 + c2 = " << m_law.c1 + m_law.c2 << " must be positive (it is half the shear modulus)";
            fail(m_c1, os.str());
        }
    }
    double shearModulus() const override { return 2.0 * (m_law.c1 + m_law.c2); }
    double bulkModulus() const override { return m_law.k; }

    core::Param<double> m_c1{this, core::ParamSpec("c1").unit("Pa").required().help("coefficient c1 of c1 (I1bar - 3) (FEBio's c1)")};
    core::Param<double> m_c2{this, core::ParamSpec("c2").unit("Pa").help("coefficient c2 of c2 (I2bar - 3) (FEBio's c2)"), 0.0};
    core::Param<double> m_k{this, core::ParamSpec("k").unit("Pa").above(0).required().help("bulk modulus k of k/2 (ln J)^2 (FEBio's k)")};
};

} // namespace fascia::materials
