#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// Compressible Mooney-Rivlin with the isochoric/volumetric split of HEML eq. (21)-(25):
/// MooneyRivlinIso plus QuadraticVolume (Laws.h). Stress-free at rest; shear modulus 2 (C1 + C2),
/// bulk kappa.
class CompressibleMooneyRivlin : public Material<CompressibleMooneyRivlinLaw> {
public:
    static constexpr const char* kName = "CompressibleMooneyRivlin";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "C1=400;C2=100;kappa=20000";
    static constexpr const char* kTitle = "Mooney-Rivlin (HEML eq. (21)-(25))";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2, I1 = tr C, I2 = (I1^2 - tr(C^2))/2, C = F^T F, J = det F; shear modulus 2 (C1 + C2), bulk modulus kappa";
    void init() override;
    double shearModulus() const override { return 2.0 * (m_law.C1 + m_law.C2); }
    double bulkModulus() const override { return m_law.kappa; }

    core::Param<double> m_C1{this, core::ParamSpec("C1").unit("Pa").required().help("coefficient C1 of C1 (I1bar - 3)")};
    core::Param<double> m_C2{this, core::ParamSpec("C2").unit("Pa").help("coefficient C2 of C2 (I2bar - 3)"), 0.0};
    core::Param<double> m_kappa{this, core::ParamSpec("kappa").unit("Pa").above(0).required().help("bulk modulus kappa of the volumetric term kappa/2 (J - 1)^2")};
};

} // namespace fascia::materials
