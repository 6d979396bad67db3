#pragma once
/// FEBio's uncoupled Mooney-Rivlin (Maas, Ellis, Ateshian & Weiss 2012, J. Biomech. Eng. 134): the
/// isochoric part of CompressibleMooneyRivlin with FEBio's volumetric part k/2 (ln J)^2, which
/// grows without bound as J -> 0 (UncoupledMooneyRivlinLaw in Laws.h).
#include "fascia/materials/Laws.h"

#include <sstream>

namespace fascia::materials {

/// FEBio's uncoupled Mooney-Rivlin (see UncoupledMooneyRivlinLaw). The parameters are FEBio's, by
/// the same names: <material type="Mooney-Rivlin"> with <c1>, <c2>, <k> becomes
/// <UncoupledMooneyRivlin c1="..." c2="..." k="..."/> (FEBio's density goes to the mass). c2 may be
/// negative, but c1 + c2 (half the shear modulus) must be positive.
class UncoupledMooneyRivlin : public Material<UncoupledMooneyRivlinLaw> {
public:
    static constexpr const char* kName = "UncoupledMooneyRivlin";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "c1=400;c2=150;k=20000";
    static constexpr const char* kTitle = "FEBio's uncoupled Mooney-Rivlin (Maas et al. 2012)";
    static constexpr const char* kTerms =
        "C1 = c1, C2 = c2 (FEBio's names), I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2, I1 = tr C, I2 = (I1^2 - tr(C^2))/2, C = F^T F, J = det F; shear modulus 2 (c1 + c2), bulk modulus k";
    void init() override {
        m_law.C1 = m_c1.get();
        m_law.C2 = m_c2.get();
        m_law.k = m_k.get();
        if (!(m_law.C1 + m_law.C2 > 0)) {
            std::ostringstream os;
            os << "c1 + c2 = " << m_law.C1 + m_law.C2 << " must be positive (it is half the shear modulus)";
            fail(m_c1, os.str());
        }
    }
    double shearModulus() const override { return 2.0 * (m_law.C1 + m_law.C2); }
    double bulkModulus() const override { return m_law.k; }

    core::Param<double> m_c1{this, core::ParamSpec("c1").unit("Pa").required().help("coefficient c1 of c1 (I1bar - 3) (FEBio's c1)")};
    core::Param<double> m_c2{this, core::ParamSpec("c2").unit("Pa").help("coefficient c2 of c2 (I2bar - 3) (FEBio's c2)"), 0.0};
    core::Param<double> m_k{this, core::ParamSpec("k").unit("Pa").above(0).required().help("bulk modulus k of k/2 (ln J)^2 (FEBio's k)")};
};

} // namespace fascia::materials
