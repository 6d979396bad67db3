#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// Compressible neo-Hookean of HEML eq. (26): LinearI1Iso plus HemlLogVolume (Laws.h).
/// Moduli: mu and lambda (C1 defaults to mu/2), or youngModulus and poissonRatio (then mu and
/// lambda are the Lame coefficients and C1 = mu/2). A C1 other than mu/2 leaves a residual stress
/// (2 C1 - mu) I at rest (warned). Shear modulus mu, bulk modulus lambda + 2 mu / 3.
class CompressibleNeoHookean : public Material<CompressibleNeoHookeanLaw> {
public:
    static constexpr const char* kName = "CompressibleNeoHookean";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "mu=1000;lambda=9000";
    static constexpr const char* kTitle = "compressible neo-Hookean (HEML eq. (26))";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "I1 = tr C, C = F^T F, J = det F, C1 = mu/2 unless given; with youngModulus E and poissonRatio nu: mu = E/(2 (1 + nu)), lambda = E nu/((1 + nu)(1 - 2 nu))";
    void init() override;
    double shearModulus() const override { return m_law.mu; }
    double bulkModulus() const override { return m_law.lambda + 2.0 / 3.0 * m_law.mu; }

    core::Param<double> m_C1{this, core::ParamSpec("C1").unit("Pa").above(0).help("coefficient C1 of C1 (I1 - 3); default mu/2, the stress-free value")};
    core::Param<double> m_mu{this, core::ParamSpec("mu").unit("Pa").above(0).help("coefficient mu of -mu ln J (the shear modulus)")};
    core::Param<double> m_lambda{this, core::ParamSpec("lambda").unit("Pa").help("coefficient lambda of lambda/2 (ln J)^2 (first Lame coefficient)")};
    core::Param<double> m_E{this, core::ParamSpec("youngModulus").unit("Pa").above(0).help("Young's modulus E (with poissonRatio, instead of mu and lambda)")};
    core::Param<double> m_nu{this, core::ParamSpec("poissonRatio").min(-1, true).below(0.5).help("Poisson's ratio nu (with youngModulus)")};
};

} // namespace fascia::materials
