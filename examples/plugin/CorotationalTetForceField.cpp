#include "CorotationalTetForceField.h"

#include "fascia/elements/Geometry.h"
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
    const auto& X = state->x0();
    for (const auto& t : m_tets)
        for (int v : t)
            if (v < 0 || size_t(v) >= X.size()) fail("a tetrahedron uses node " + std::to_string(v) + " of " + std::to_string(X.size()));
    m_assembly.init(m_tets, X.size());  // sorts the elements by lowest node, fixed blocks
    m_mu = m_E.get() / (2 * (1 + m_nu.get()));
    m_lambda = m_E.get() * m_nu.get() / ((1 + m_nu.get()) * (1 - 2 * m_nu.get()));
    const size_t n = m_tets.size();
    m_DmInv.resize(n);
    m_vol.resize(n);
    m_altitude.resize(n);
    for (size_t e = 0; e < n; ++e) {
        const auto& t = m_tets[e];
        Mat3 Dm;
        Dm << X[t[1]] - X[t[0]], X[t[2]] - X[t[0]], X[t[3]] - X[t[0]];
        const double det = Dm.determinant();
        if (!(det > 0)) fail("element " + std::to_string(e) + " is inverted or flat at rest");
        m_DmInv[e] = Dm.inverse();
        m_vol[e] = det / 6;
        m_altitude[e] = elements::tetAltitude(X[t[0]], X[t[1]], X[t[2]], X[t[3]], m_vol[e]);
    }
}

double CorotationalTetForceField::elementStress(const fascia::Positions& x, size_t e, Mat3& P) const {
    const auto& t = m_tets[e];
    Mat3 Ds;
    Ds << x[t[1]] - x[t[0]], x[t[2]] - x[t[0]], x[t[3]] - x[t[0]];
    const Mat3 F = Ds * m_DmInv[e];
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
    return m_vol[e] * (m_mu * Sm.squaredNorm() + 0.5 * m_lambda * tr * tr);
}

void CorotationalTetForceField::addForce(fascia::core::BaseMechanicalState& s, fascia::Positions& f, double) {
    m_assembly.addForces(m_tets, f.data()->data(), [&](size_t e, Vec3 (&fe)[4]) {
        Mat3 P;
        elementStress(s.x(), e, P);
        const Mat3 H = -m_vol[e] * P * m_DmInv[e].transpose();  // forces on nodes 1..3
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
    const double rho = elements::densityFor(*mass, std::accumulate(m_vol.begin(), m_vol.end(), 0.0));
    const double c = std::sqrt((m_lambda + 2 * m_mu) / rho);  // dilatational wave speed
    double L = INFINITY;
    for (double h : m_altitude) L = std::min(L, h);
    return rho > 0 ? L / c : INFINITY;
}

} // namespace example
