#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// The HEML paper's "incompressible" Mooney-Rivlin (Table 3): LinearI1I2Iso, no volumetric part,
/// not stress-free at rest (S = 2 (C1 + 2 C2) I at C = I).
/// Shear modulus 2 (C1 + C2); bulk modulus reported as 0.
class IncompressibleMooneyRivlin : public Material<IncompressibleMooneyRivlinLaw> {
public:
    static constexpr const char* kName = "IncompressibleMooneyRivlin";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "C1=400;C2=100";
    static constexpr const char* kTitle = "HEML's Mooney-Rivlin, no volumetric term (HEML Table 3)";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "I1 = tr C, I2 = (I1^2 - tr(C^2))/2, C = F^T F; not stress-free at rest (S = 2 (C1 + 2 C2) I at C = I): ViscoelasticProny only with apply=\"isochoric\"";
    void init() override;
    double shearModulus() const override { return 2.0 * (m_law.C1 + m_law.C2); }
    double bulkModulus() const override { return 0.0; }

    core::Param<double> m_C1{this, core::ParamSpec("C1").unit("Pa").required().help("Mooney-Rivlin coefficient C1 (of I1 - 3)")};
    core::Param<double> m_C2{this, core::ParamSpec("C2").unit("Pa").help("Mooney-Rivlin coefficient C2 (of I2 - 3)"), 0.0};
};

} // namespace fascia::materials
