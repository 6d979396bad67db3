#pragma once
#include "fascia/materials/Laws.h"

namespace fascia::materials {

/// Orthotropic neo-Hookean (TLED section 3.2.3): two fibre families a0, b0 in the eq. (33)
/// convention,
/// OrthotropicIso plus QuadraticVolume (Laws.h).
/// `direction` is a0, `direction2` is b0 (both normalised; they must not be parallel and should be
/// orthogonal, warned otherwise). Stress-free at rest.
class Orthotropic : public Material<OrthotropicLaw> {
public:
    static constexpr const char* kName = "Orthotropic";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "mu=1000;kappa=20000;eta=3000;eta2=1500;direction=1 0 0;direction2=0 1 0";
    static constexpr const char* kTitle = "orthotropic neo-Hookean, two fibre families (TLED section 3.2.3)";
    /// what --describe prints after W: the invariants, the parameter conversions, the moduli
    static constexpr const char* kTerms =
        "I1bar = J^(-2/3) tr C, I4bar = J^(-2/3) a0.C a0, I6bar = J^(-2/3) b0.C b0, C = F^T F, J = det F, a0 = direction, b0 = direction2; with youngModulus E and poissonRatio nu: mu = E/(2 (1 + nu)), kappa = E/(3 (1 - 2 nu))";
    void init() override;
    double shearModulus() const override { return m_law.mu; }
    double bulkModulus() const override { return m_law.kappa; }
    /// Upper bound of the dilatational wave speed: sqrt((kappa + 4/3 mu + eta + eta2)/rho).
    double waveSpeed(double rho) const override;
    const Vec3* fibreDirection(int which) const override {
        return which == 0 ? &m_a0 : which == 1 ? &m_b0 : nullptr;
    }
    const Vec3& direction() const { return m_a0; }   ///< unit a0
    const Vec3& direction2() const { return m_b0; }  ///< unit b0

    core::Param<double> m_mu{this, core::ParamSpec("mu").unit("Pa").above(0).help("shear modulus mu")};
    core::Param<double> m_kappa{this, core::ParamSpec("kappa").unit("Pa").above(0).help("bulk modulus kappa of kappa/2 (J - 1)^2")};
    core::Param<double> m_E{this, core::ParamSpec("youngModulus").unit("Pa").above(0).help("Young's modulus E of the isotropic part (with poissonRatio, instead of mu and kappa)")};
    core::Param<double> m_nu{this, core::ParamSpec("poissonRatio").min(-1, true).below(0.5).help("Poisson's ratio nu of the isotropic part (with youngModulus)")};
    core::Param<double> m_eta{this, core::ParamSpec("eta").unit("Pa").min(0).help("stiffness eta of the first fibre family, eta/4 (I4bar - 1)^2"), 0.0};
    core::Param<double> m_eta2{this, core::ParamSpec("eta2").unit("Pa").min(0).help("stiffness eta2 of the second fibre family, eta2/4 (I6bar - 1)^2"), 0.0};
    core::Param<Vec3> m_dir{this, core::ParamSpec("direction").help("first fibre direction a0 (normalised)"), Vec3(0, 0, 1)};
    core::Param<Vec3> m_dir2{this, core::ParamSpec("direction2").help("second fibre direction b0 (normalised), orthogonal to direction"), Vec3(1, 0, 0)};

private:
    Vec3 m_a0 = Vec3(0, 0, 1), m_b0 = Vec3(1, 0, 0);
};

} // namespace fascia::materials
