#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// Transversely isotropic neo-Hookean (TLED section 3.2.2, eq. (31)-(33), Appendix A):
/// TransverselyIsotropicIso plus QuadraticVolume (Laws.h), in the eq. (33) convention (eq. (31)
/// prints eta/2: see TransverselyIsotropicIso).
/// The fibre direction a0 is `direction` (normalised); force fields may override it per element
/// from a mesh cell array. Stress-free at rest.
class TransverselyIsotropic : public Material<TransverselyIsotropicLaw> {
public:
    static constexpr const char* kName = "TransverselyIsotropic";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "mu=1000;kappa=20000;eta=3000;direction=1 1 0";
    static constexpr const char* kTitle = "transversely isotropic neo-Hookean, fibres in the TLED eq. (33) convention (TLED section 3.2.2)";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "I1bar = J^(-2/3) tr C, I4bar = J^(-2/3) a0.C a0, C = F^T F, J = det F, a0 = direction (TLED eq. (31) with eq. (33)'s factor eta/4, see Laws.h); with youngModulus E and poissonRatio nu: mu = E/(2 (1 + nu)), kappa = E/(3 (1 - 2 nu))";
    void init() override;
    double shearModulus() const override { return m_law.mu; }
    double bulkModulus() const override { return m_law.kappa; }
    /// Upper bound of the dilatational wave speed: sqrt((kappa + 4/3 mu + eta)/rho)
    /// (the fibre term adds 8/9 eta to the P-wave modulus along a0).
    double waveSpeed(double rho) const override;
    const Vec3* fibreDirection(int which) const override { return which == 0 ? &m_a0 : nullptr; }
    /// Unit fibre direction a0.
    const Vec3& direction() const { return m_a0; }

    core::Param<double> m_mu{this, core::ParamSpec("mu").unit("Pa").above(0).help("shear modulus mu")};
    core::Param<double> m_kappa{this, core::ParamSpec("kappa").unit("Pa").above(0).help("bulk modulus kappa of kappa/2 (J - 1)^2")};
    core::Param<double> m_E{this, core::ParamSpec("youngModulus").unit("Pa").above(0).help("Young's modulus E of the isotropic part (with poissonRatio, instead of mu and kappa)")};
    core::Param<double> m_nu{this, core::ParamSpec("poissonRatio").min(-1, true).below(0.5).help("Poisson's ratio nu of the isotropic part (with youngModulus)")};
    core::Param<double> m_eta{this, core::ParamSpec("eta").unit("Pa").min(0).help("fibre stiffness eta of eta/4 (I4bar - 1)^2 (TLED eq. (33) convention)"), 0.0};
    core::Param<Vec3> m_dir{this, core::ParamSpec("direction").help("fibre direction a0 in the reference configuration (normalised)"), Vec3(0, 0, 1)};

private:
    Vec3 m_a0 = Vec3(0, 0, 1);
};

} // namespace fascia::materials
