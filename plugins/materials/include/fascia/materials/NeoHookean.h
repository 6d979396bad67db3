#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// Neo-Hookean with the isochoric split (TLED eq. (9), (31)-(32) without fibres): NeoHookeanLaw,
/// NeoHookeanIso plus QuadraticVolume (Laws.h; W is their kEnergy texts).
/// Moduli: mu and kappa, or youngModulus and poissonRatio. Stress-free at rest.
class NeoHookean : public Material<NeoHookeanLaw> {
public:
    static constexpr const char* kName = "NeoHookean";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "mu=1000;kappa=20000";
    static constexpr const char* kTitle = "neo-Hookean (TLED eq. (31)-(32), no fibres)";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "I1bar = J^(-2/3) I1, I1 = tr C, C = F^T F, J = det F; with youngModulus E and poissonRatio nu: mu = E/(2 (1 + nu)), kappa = E/(3 (1 - 2 nu))";
    void init() override;
    double shearModulus() const override { return m_law.mu; }
    double bulkModulus() const override { return m_law.kappa; }

    core::Param<double> m_mu{this, core::ParamSpec("mu").unit("Pa").above(0).help("shear modulus mu")};
    core::Param<double> m_kappa{this, core::ParamSpec("kappa").unit("Pa").above(0).help("bulk modulus kappa of kappa/2 (J - 1)^2")};
    core::Param<double> m_E{this, core::ParamSpec("youngModulus").unit("Pa").above(0).help("Young's modulus E (with poissonRatio, instead of mu and kappa)")};
    core::Param<double> m_nu{this, core::ParamSpec("poissonRatio").min(-1, true).below(0.5).help("Poisson's ratio nu (with youngModulus)")};
};

} // namespace fascia::materials
