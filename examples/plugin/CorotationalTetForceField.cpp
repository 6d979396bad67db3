#include "CorotationalTetForceField.h"
#include "fascia/scene/Node.h"

#include <Eigen/SVD>
#include <cmath>

namespace example {

using fascia::Mat3;
using fascia::Vec3;

void CorotationalTetForceField::init() {
    auto* topo = node()->findInContext<fascia::core::BaseTopology>();
    auto* state = node()->findInContext<fascia::core::BaseMechanicalState>();
    if (!topo || !state) fail("needs a mesh source (MeshLoader, GridMesh) and a MechanicalObject in its context");
    if (topo->meshData().points.size() != state->size())
        fail("the mesh source has " + std::to_string(topo->meshData().points.size()) + " points, the state " +
             std::to_string(state->size()) + " nodes");
    m_tets = topo->meshData().tetrahedra;
    if (m_tets.empty()) fail("the mesh has no tetrahedra");
    const double E = m_E.get(), nu = m_nu.get();
    m_mu = E / (2 * (1 + nu));
    m_lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    const auto& X = state->x0();
    m_DmInv.resize(m_tets.size());
    m_vol.resize(m_tets.size());
    m_minHeight = INFINITY;
    for (size_t e = 0; e < m_tets.size(); ++e) {
        const auto& t = m_tets[e];
        Mat3 Dm;
        Dm << X[t[1]] - X[t[0]], X[t[2]] - X[t[0]], X[t[3]] - X[t[0]];
        const double det = Dm.determinant();
        if (!(det > 0)) fail("element " + std::to_string(e) + " is inverted or flat at rest");
        m_DmInv[e] = Dm.inverse();
        m_vol[e] = det / 6;
        // smallest height = 3 Vol / largest face area
        double area = 0;
        for (int k = 0; k < 4; ++k) {
            const Vec3& a = X[t[(k + 1) % 4]];
            area = std::max(area, 0.5 * (X[t[(k + 2) % 4]] - a).cross(X[t[(k + 3) % 4]] - a).norm());
        }
        m_minHeight = std::min(m_minHeight, 3 * m_vol[e] / area);
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
    const auto& x = s.x();
    for (size_t e = 0; e < m_tets.size(); ++e) {
        Mat3 P;
        elementStress(x, e, P);
        const Mat3 H = -m_vol[e] * P * m_DmInv[e].transpose();  // forces on nodes 1..3
        const auto& t = m_tets[e];
        for (int k = 0; k < 3; ++k) {
            f[t[k + 1]] += H.col(k);
            f[t[0]] -= H.col(k);
        }
    }
}

double CorotationalTetForceField::potentialEnergy(const fascia::core::BaseMechanicalState& s) const {
    double W = 0;
    Mat3 P;
    for (size_t e = 0; e < m_tets.size(); ++e) W += elementStress(s.x(), e, P);
    return W;
}

double CorotationalTetForceField::stableTimeStep(const fascia::core::BaseMechanicalState&) const {
    auto* mass = node()->findInContext<fascia::core::BaseMass>();
    const double rho = mass ? mass->density() : NAN;
    if (!(rho > 0)) return INFINITY;
    return m_minHeight / std::sqrt((m_lambda + 2 * m_mu) / rho);
}

} // namespace example
