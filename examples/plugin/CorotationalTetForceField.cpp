#include "CorotationalTetForceField.h"

#include "fascia/scene/Node.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace example {

using fascia::Mat3;
using fascia::Vec3;
namespace elements = fascia::elements;

void CorotationalTetForceField::init() {
    auto* topo = node()->findInContext<fascia::core::BaseTopology>();
    auto* state = node()->findInContext<fascia::core::BaseMechanicalState>();
    if (!topo || !state) fail("needs a mesh source (MeshLoader, GridMesh) and a MechanicalObject in its context");
    m_tets = topo->meshData().tetrahedra;
    if (m_tets.empty()) fail("the mesh has no tetrahedra");
    m_mu = m_E.get() / (2 * (1 + m_nu.get()));
    m_lambda = m_E.get() * m_nu.get() / ((1 + m_nu.get()) * (1 - 2 * m_nu.get()));
    m_assembly.init(m_tets, state->size());           // elements sorted by lowest node, fixed blocks
    m_rest = elements::tetRest(*this, state->x0(), m_tets);  // Dm^-1, volumes, altitudes
}

double CorotationalTetForceField::elementStress(const fascia::Positions& x, size_t e, Mat3& P) const {
    const auto& t = m_tets[e];
    Mat3 Ds;
    Ds << x[t[1]] - x[t[0]], x[t[2]] - x[t[0]], x[t[3]] - x[t[0]];
    const Mat3 F = Ds * m_rest.DmInv[e];
    Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Mat3 U = svd.matrixU(), V = svd.matrixV();
    Vec3 sig = svd.singularValues();
    if ((U * V.transpose()).determinant() < 0) {  // a proper rotation: flip the smallest singular value
        U.col(2) *= -1;
        sig[2] *= -1;
    }
    const Mat3 R = U * V.transpose();
    const Mat3 Sm = V * sig.asDiagonal() * V.transpose() - Mat3::Identity();
    const double tr = Sm.trace();
    P = R * (2 * m_mu * Sm + m_lambda * tr * Mat3::Identity());
    return m_rest.volume[e] * (m_mu * Sm.squaredNorm() + 0.5 * m_lambda * tr * tr);
}

void CorotationalTetForceField::addForce(fascia::core::BaseMechanicalState& s, fascia::Positions& f, double) {
    // on all threads, the same forces for any thread count (fascia/elements/ElementAssembly.h)
    m_assembly.addForces(m_tets, f.data()->data(), [&](size_t e, Vec3 (&fe)[4]) {
        Mat3 P;
        elementStress(s.x(), e, P);
        const Mat3 H = -m_rest.volume[e] * P * m_rest.DmInv[e].transpose();  // forces on nodes 1..3
        for (int k = 0; k < 3; ++k) {
            fe[k + 1] = H.col(k);
            fe[0] -= H.col(k);
        }
    });
}

double CorotationalTetForceField::potentialEnergy(const fascia::core::BaseMechanicalState& s) const {
    double W = 0;
    Mat3 P;
    for (size_t e = 0; e < m_tets.size(); ++e) W += elementStress(s.x(), e, P);
    return W;
}

double CorotationalTetForceField::stableTimeStep(const fascia::core::BaseMechanicalState&) const {
    auto* mass = node()->findInContext<fascia::core::BaseMass>();
    if (!mass) return INFINITY;
    const auto& V = m_rest.volume;
    const double rho = elements::densityFor(*mass, std::accumulate(V.begin(), V.end(), 0.0));
    const double L = *std::min_element(m_rest.altitude.begin(), m_rest.altitude.end());
    return rho > 0 ? L / std::sqrt((m_lambda + 2 * m_mu) / rho) : INFINITY;  // altitude / dilatational wave speed
}

} // namespace example
