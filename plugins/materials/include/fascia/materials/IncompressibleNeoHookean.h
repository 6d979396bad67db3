#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// The HEML paper's "incompressible" neo-Hookean (Table 3): LinearI1Iso, no volumetric part (Laws.h).
/// Incompressible only in the paper's sense: nothing enforces J = 1 and the rest state carries
/// the stress S = 2 C1 I (not stress-free). Shear modulus 2 C1; bulk modulus reported as 0.
class IncompressibleNeoHookean : public Material<IncompressibleNeoHookeanLaw> {
public:
    static constexpr const char* kName = "IncompressibleNeoHookean";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "C1=500";
    static constexpr const char* kTitle = "HEML's neo-Hookean, no volumetric term (HEML Table 3)";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "I1 = tr C, C = F^T F; not stress-free at rest (S = 2 C1 I at C = I): ViscoelasticProny only with apply=\"isochoric\"";
    void init() override { m_law.C1 = m_C1.get(); }
    double shearModulus() const override { return 2.0 * m_law.C1; }
    double bulkModulus() const override { return 0.0; }

    core::Param<double> m_C1{this, core::ParamSpec("C1").unit("Pa").above(0).required().help("neo-Hookean coefficient C1 of W = C1 (I1 - 3)")};
};

} // namespace fascia::materials
