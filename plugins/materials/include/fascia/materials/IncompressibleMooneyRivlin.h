#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// The HEML paper's "incompressible" Mooney-Rivlin (Table 3): W = C1 (I1 - 3) + C2 (I2 - 3),
/// no volumetric term, not stress-free at rest (S = 2 (C1 + 2 C2) I at C = I).
/// Shear modulus 2 (C1 + C2); bulk modulus reported as 0.
class IncompressibleMooneyRivlin : public Material<IncompressibleMooneyRivlinLaw> {
public:
    static constexpr const char* kName = "IncompressibleMooneyRivlin";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "C1=400;C2=100";
    static constexpr const char* kDescription = "HEML's Mooney-Rivlin C1 (I1 - 3) + C2 (I2 - 3), no volumetric term (HEML Table 3)";
    /// the energy in full, for --describe (a second line of the registry description)
    static constexpr const char* kEnergy =
        "W = C1 (I1 - 3) + C2 (I2 - 3), I1 = tr C, I2 = (I1^2 - tr(C^2))/2, C = F^T F; no volumetric term and not stress-free at rest (S = 2 (C1 + 2 C2) I at C = I); ViscoelasticProny relaxes W - 2 (C1 + 2 C2) ln J (apply=\"isochoric\" only) (HEML Table 3)";
    void init() override;
    double shearModulus() const override { return 2.0 * (m_law.C1 + m_law.C2); }
    double bulkModulus() const override { return 0.0; }

    core::Param<double> m_C1{this, core::ParamSpec("C1").unit("Pa").required().help("Mooney-Rivlin coefficient C1 (of I1 - 3)")};
    core::Param<double> m_C2{this, core::ParamSpec("C2").unit("Pa").help("Mooney-Rivlin coefficient C2 (of I2 - 3)"), 0.0};
};

} // namespace fascia::materials
