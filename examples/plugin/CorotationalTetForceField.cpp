#include "CorotationalTetForceField.h"

#include <Eigen/SVD>
#include <cmath>

namespace example {

using fascia::Mat3;

void CorotationalTetForceField::initElements() {
    m_mu = m_E.get() / (2 * (1 + m_nu.get()));
    m_lambda = m_E.get() * m_nu.get() / ((1 + m_nu.get()) * (1 - 2 * m_nu.get()));
}

double CorotationalTetForceField::stress(const Mat3& F, Mat3& P) const {
    Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Mat3 U = svd.matrixU(), V = svd.matrixV();
    fascia::Vec3 sig = svd.singularValues();
    if ((U * V.transpose()).determinant() < 0) {  // a proper rotation: flip the smallest singular value
        U.col(2) *= -1;
        sig[2] *= -1;
    }
    const Mat3 R = U * V.transpose();
    const Mat3 Sm = V * sig.asDiagonal() * V.transpose() - Mat3::Identity();
    const double tr = Sm.trace();
    P = R * (2 * m_mu * Sm + m_lambda * tr * Mat3::Identity());
    return m_mu * Sm.squaredNorm() + 0.5 * m_lambda * tr * tr;
}

double CorotationalTetForceField::waveSpeed(double rho) const { return std::sqrt((m_lambda + 2 * m_mu) / rho); }

} // namespace example
