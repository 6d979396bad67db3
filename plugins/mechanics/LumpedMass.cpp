#include "LumpedMass.h"
#include "fascia/scene/Node.h"

#include <Eigen/Dense>

#include <cmath>

namespace fascia::mechanics {

double tetVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

double hexVolume(const Positions& x, const std::array<int, 8>& h) {
    // reference corners in VTK order
    static const double s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const double g = 1.0 / std::sqrt(3.0);
    double vol = 0;
    for (int q = 0; q < 8; ++q) {
        const double p[3] = {s[q][0] * g, s[q][1] * g, s[q][2] * g};
        Mat3 J = Mat3::Zero();
        for (int a = 0; a < 8; ++a) {
            const double dN[3] = {s[a][0] * (1 + s[a][1] * p[1]) * (1 + s[a][2] * p[2]) / 8,
                                  s[a][1] * (1 + s[a][0] * p[0]) * (1 + s[a][2] * p[2]) / 8,
                                  s[a][2] * (1 + s[a][0] * p[0]) * (1 + s[a][1] * p[1]) / 8};
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) J(i, j) += x[h[a]][i] * dN[j];
        }
        vol += J.determinant();  // unit Gauss weights
    }
    return vol;
}

void LumpedMass::init() {
    if (m_density.isSet() == m_totalMass.isSet())
        fail(m_density.isSet() ? "give density or totalMass, not both" : "give density (kg/m^3) or totalMass (kg)");
    auto* state = node()->findInContext<core::BaseMechanicalState>();
    if (!state) fail("no MechanicalObject in its context");
    const size_t n = state->size();
    m_masses.assign(n, 0.0);
    const Positions& X = state->x0();
    m_volume = 0;
    if (auto* topo = node()->findInContext<core::BaseTopology>()) {
        const MeshData& mesh = topo->meshData();
        if (mesh.points.size() != n)
            fail("the mesh source '" + topo->name() + "' has " + std::to_string(mesh.points.size()) +
                 " points but the state '" + state->name() + "' has " + std::to_string(n) + " nodes");
        for (auto& t : mesh.tetrahedra) {
            const double v = std::abs(tetVolume(X[t[0]], X[t[1]], X[t[2]], X[t[3]]));
            m_volume += v;
            for (int k : t) m_masses[k] += v / 4;
        }
        for (auto& h : mesh.hexahedra) {
            const double v = std::abs(hexVolume(X, h));
            m_volume += v;
            for (int k : h) m_masses[k] += v / 8;
        }
    }
    if (m_volume > 0) {
        m_rho = m_density.isSet() ? m_density.get() : m_totalMass.get() / m_volume;
        for (double& m : m_masses) m *= m_rho;
    } else if (m_totalMass.isSet()) {
        // a point cloud: the total mass shared equally
        for (double& m : m_masses) m = m_totalMass.get() / double(n);
        m_rho = std::nan("");
    } else {
        fail(m_density, "density needs volume elements, but no mesh with tetrahedra or hexahedra is in the context; "
                        "give totalMass instead");
    }
}

} // namespace fascia::mechanics
