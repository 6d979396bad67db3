#pragma once
#include "fascia/elements/ElementAssembly.h"
#include "fascia/elements/Geometry.h"
#include "fascia/sim/Mechanics.h"

#include <vector>

namespace example {

/// Corotational linear elasticity on tetrahedra, the classic fast baseline: with F = R S the polar
/// decomposition of the deformation gradient, the energy density is
///   W = mu |S - I|^2 + lambda/2 tr(S - I)^2,  P = dW/dF = R (2 mu (S - I) + lambda tr(S - I) I),
/// and f = -Vol P grad(N). Linear elasticity for small strains, invariant under rotation.
/// Built on the element layer (fascia/elements): its geometry, stable time step and deterministic
/// block buffers, so it runs on all threads with the same forces for any thread count.
class CorotationalTetForceField : public fascia::core::BaseForceField {
public:
    void init() override;
    void addForce(fascia::core::BaseMechanicalState& s, fascia::Positions& f, double t) override;
    double potentialEnergy(const fascia::core::BaseMechanicalState& s) const override;
    double stableTimeStep(const fascia::core::BaseMechanicalState& s) const override;
    size_t elementCount() const override { return m_tets.size(); }
    const fascia::Tetrahedra* tetrahedra() const override { return &m_tets; }

    fascia::core::Param<double> m_E{this, fascia::core::ParamSpec("youngModulus").unit("Pa").above(0).required().help("Young's modulus E")};
    fascia::core::Param<double> m_nu{this, fascia::core::ParamSpec("poissonRatio").min(-1, true).below(0.5).help("Poisson's ratio"), 0.3};

private:
    /// P and W of one element at the given positions.
    double elementStress(const fascia::Positions& x, size_t e, fascia::Mat3& P) const;
    fascia::Tetrahedra m_tets;              ///< sorted by lowest node (ElementAssembly::init)
    fascia::elements::TetRest m_rest;       ///< Dm^-1, volumes and altitudes at rest
    fascia::elements::ElementAssembly m_assembly;  ///< fixed blocks of elements, one node buffer each
    double m_mu = 0, m_lambda = 0;
};

} // namespace example
