#pragma once
#include "fascia/elements/TetForceField.h"

namespace example {

/// Corotational linear elasticity on tetrahedra, the classic fast baseline: with F = R S the polar
/// decomposition of the deformation gradient, the energy density is
///   W = mu |S - I|^2 + lambda/2 tr(S - I)^2,  P = dW/dF = R (2 mu (S - I) + lambda tr(S - I) I).
/// Linear elasticity for small strains, invariant under rotation. The element layer's
/// TetForceField does the rest: the mesh, the geometry, f = -Vol P grad(N) on all threads (the same
/// forces for any thread count), the energy and the stable time step.
class CorotationalTetForceField : public fascia::elements::TetForceField<CorotationalTetForceField> {
public:
    void initElements();
    /// W (J/m^3) and P = dW/dF (Pa) at F.
    double stress(const fascia::Mat3& F, fascia::Mat3& P) const;
    /// Dilatational wave speed sqrt((lambda + 2 mu) / rho) (m/s).
    double waveSpeed(double rho) const;

    fascia::core::Param<double> m_E{this, fascia::core::ParamSpec("youngModulus").unit("Pa").above(0).required().help("Young's modulus E")};
    fascia::core::Param<double> m_nu{this, fascia::core::ParamSpec("poissonRatio").min(-1, true).below(0.5).help("Poisson's ratio"), 0.3};

private:
    double m_mu = 0, m_lambda = 0;
};

} // namespace example
