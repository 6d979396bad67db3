#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// Saint Venant-Kirchhoff material (HEML Table 3): StVenantKirchhoffIso, no volumetric part (Laws.h).
/// Moduli: lambda and mu, or youngModulus and poissonRatio. No volumetric term; softens under
/// strong compression (HEML section 4.2). Shear modulus mu, bulk modulus lambda + 2 mu / 3.
class StVenantKirchhoff : public Material<StVenantKirchhoffLaw> {
public:
    static constexpr const char* kName = "StVenantKirchhoff";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "youngModulus=3000;poissonRatio=0.45";
    static constexpr const char* kTitle = "Saint Venant-Kirchhoff (HEML Table 3)";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "E = (C - I)/2 (Green-Lagrange strain), C = F^T F; written as lambda/8 (I1 - 3)^2 + mu/4 (I1^2 - 2 I2 - 2 I1 + 3); lambda, mu from youngModulus, poissonRatio as the Lame coefficients";
    void init() override;
    double shearModulus() const override { return m_law.mu; }
    double bulkModulus() const override { return m_law.lambda + 2.0 / 3.0 * m_law.mu; }

    core::Param<double> m_lambda{this, core::ParamSpec("lambda").unit("Pa").help("first Lame coefficient lambda (or give youngModulus and poissonRatio)")};
    core::Param<double> m_mu{this, core::ParamSpec("mu").unit("Pa").above(0).help("shear modulus mu, the second Lame coefficient")};
    core::Param<double> m_E{this, core::ParamSpec("youngModulus").unit("Pa").above(0).help("Young's modulus E (with poissonRatio, instead of lambda and mu)")};
    core::Param<double> m_nu{this, core::ParamSpec("poissonRatio").min(-1, true).below(0.5).help("Poisson's ratio nu (with youngModulus)")};
};

} // namespace fascia::materials
