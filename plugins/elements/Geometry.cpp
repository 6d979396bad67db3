#include "fascia/elements/Geometry.h"
#include "fascia/elements/EdgeForm.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace fascia::elements {

const double kHexXi[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const double kHourglass[4][8] = {{1, -1, 1, -1, 1, -1, 1, -1},
                                 {1, 1, -1, -1, -1, -1, 1, 1},
                                 {1, -1, -1, 1, -1, 1, 1, -1},
                                 {-1, 1, -1, 1, 1, -1, 1, -1}};

double tetSignedVolume6(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
    Mat3 D;
    D.col(0) = p1 - p0;
    D.col(1) = p2 - p0;
    D.col(2) = p3 - p0;
    return D.determinant();
}

double tetLongestEdge(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
    const Vec3* p[4] = {&p0, &p1, &p2, &p3};
    double longest = 0;
    for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) longest = std::max(longest, (*p[a] - *p[b]).norm());
    return longest;
}

double tetAltitude(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double V) {
    const Vec3* p[4] = {&p0, &p1, &p2, &p3};
    double maxFace = 0;
    for (int f = 0; f < 4; ++f) {
        const Vec3& a = *p[(f + 1) % 4];
        const Vec3& b = *p[(f + 2) % 4];
        const Vec3& c = *p[(f + 3) % 4];
        maxFace = std::max(maxFace, 0.5 * (b - a).cross(c - a).norm());
    }
    return 3.0 * V / maxFace;
}

double hexCharacteristicLength(const Vec3 (&p)[8], double V) {
    static const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    double amax = 0;
    for (auto& f : faces) amax = std::max(amax, 0.5 * (p[f[2]] - p[f[0]]).cross(p[f[3]] - p[f[1]]).norm());
    return V / amax;
}

namespace {
double det3(const double m[9]) {
    return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
}
void cof3(const double m[9], double c[9]) {
    c[0] = m[4] * m[8] - m[5] * m[7];
    c[1] = m[5] * m[6] - m[3] * m[8];
    c[2] = m[3] * m[7] - m[4] * m[6];
    c[3] = m[2] * m[7] - m[1] * m[8];
    c[4] = m[0] * m[8] - m[2] * m[6];
    c[5] = m[1] * m[6] - m[0] * m[7];
    c[6] = m[1] * m[5] - m[2] * m[4];
    c[7] = m[2] * m[3] - m[0] * m[5];
    c[8] = m[0] * m[4] - m[1] * m[3];
}
} // namespace

void hexUniformStrain(const Vec3 (&P)[8], double& V, double dN[24], double& sumDN2) {
    // (1/V) int dN/dX dV = (1/V) int cof(J) dN/dxi dxi and V = int det J dxi, 2x2x2 Gauss points
    const double gp = 1.0 / std::sqrt(3.0);
    V = 0;
    double Bs[8][3] = {};
    for (int q = 0; q < 8; ++q) {
        const double g3[3] = {kHexXi[q][0] * gp, kHexXi[q][1] * gp, kHexXi[q][2] * gp};
        double dxi[8][3];
        for (int a = 0; a < 8; ++a) {
            const double f[3] = {1 + kHexXi[a][0] * g3[0], 1 + kHexXi[a][1] * g3[1], 1 + kHexXi[a][2] * g3[2]};
            dxi[a][0] = 0.125 * kHexXi[a][0] * f[1] * f[2];
            dxi[a][1] = 0.125 * kHexXi[a][1] * f[0] * f[2];
            dxi[a][2] = 0.125 * kHexXi[a][2] * f[0] * f[1];
        }
        double J[9] = {};
        for (int a = 0; a < 8; ++a)
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) J[3 * i + j] += P[a][i] * dxi[a][j];
        double cj[9];
        cof3(J, cj);
        V += det3(J);
        for (int a = 0; a < 8; ++a)
            for (int i = 0; i < 3; ++i) Bs[a][i] += cj[3 * i] * dxi[a][0] + cj[3 * i + 1] * dxi[a][1] + cj[3 * i + 2] * dxi[a][2];
    }
    sumDN2 = 0;
    for (int a = 0; a < 8; ++a)
        for (int i = 0; i < 3; ++i) {
            dN[3 * a + i] = Bs[a][i] / V;
            sumDN2 += dN[3 * a + i] * dN[3 * a + i];
        }
}

void hexHourglassVectors(const Vec3 (&P)[8], double c[12]) {
    for (int r = 0; r < 12; ++r) c[r] = 0;
    for (int q = 0; q < 4; ++q)
        for (int a = 0; a < 8; ++a)
            for (int i = 0; i < 3; ++i) c[3 * q + i] += kHourglass[q][a] * P[a][i];
}

double hexHourglassStiffness(double kappa, const materials::BaseMaterial& m, double absV, double sumDN2) {
    const double pModulus = m.bulkModulus() + 4.0 / 3.0 * m.shearModulus();
    return kappa * pModulus * absV * sumDN2 / 8.0;
}

TetRest tetRest(const core::Component& owner, const Positions& X, const Tetrahedra& tets) {
    TetRest r;
    for (size_t e = 0; e < tets.size(); ++e) {
        const auto& t = tets[e];
        for (int v : t)
            if (v < 0 || size_t(v) >= X.size())
                owner.fail("tetrahedron " + std::to_string(e) + " uses node " + std::to_string(v) + " but there are " +
                           std::to_string(X.size()) + " nodes");
        Mat3 Dm;
        Dm << X[t[1]] - X[t[0]], X[t[2]] - X[t[0]], X[t[3]] - X[t[0]];
        const double det = Dm.determinant();
        if (!(det > 0)) owner.fail("tetrahedron " + std::to_string(e) + " is inverted or flat at rest");
        r.DmInv.push_back(Dm.inverse());
        r.volume.push_back(det / 6);
        r.altitude.push_back(tetAltitude(X[t[0]], X[t[1]], X[t[2]], X[t[3]], det / 6));
    }
    return r;
}

namespace {
/// det(dx/dxi) at the centre of a hexahedron: dN_a/dxi_i = xi_a,i / 8 there.
double hexCentreJacobian(const Positions& p, const std::array<int, 8>& h) {
    Mat3 J = Mat3::Zero();
    for (int a = 0; a < 8; ++a)
        for (int i = 0; i < 3; ++i) J.col(i) += (kHexXi[a][i] / 8.0) * p[size_t(h[size_t(a)])];
    return J.determinant();
}
} // namespace

bool worstElement(const Tetrahedra& tets, const Hexahedra& hexes, const Positions& X, const Positions& x,
                  core::ElementReport& out) {
    const size_t n = std::min(X.size(), x.size());
    bool found = false;
    auto consider = [&](long index, double J, const Vec3& centroid) {
        core::ElementReport r{index, J, centroid};
        if (!found || core::worseElement(r, out)) out = r, found = true;
    };
    for (size_t e = 0; e < tets.size(); ++e) {
        const auto& t = tets[e];
        if (size_t(*std::max_element(t.begin(), t.end())) >= n || *std::min_element(t.begin(), t.end()) < 0) return false;
        const double V0 = tetSignedVolume6(X[t[0]], X[t[1]], X[t[2]], X[t[3]]);
        const double V = tetSignedVolume6(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
        consider(long(e), V / V0, (X[t[0]] + X[t[1]] + X[t[2]] + X[t[3]]) / 4.0);
    }
    for (size_t e = 0; e < hexes.size(); ++e) {
        const auto& h = hexes[e];
        if (size_t(*std::max_element(h.begin(), h.end())) >= n || *std::min_element(h.begin(), h.end()) < 0) return false;
        Vec3 c = Vec3::Zero();
        for (int a : h) c += X[size_t(a)] / 8.0;
        consider(long(tets.size() + e), hexCentreJacobian(x, h) / hexCentreJacobian(X, h), c);
    }
    return found;
}

double densityFor(const core::BaseMass& mass, double restVolume) {
    double rho = mass.density();
    if (std::isfinite(rho)) return rho;
    double M = 0;
    for (double m : mass.nodalMasses()) M += m;
    return restVolume > 0 ? M / restVolume : std::numeric_limits<double>::quiet_NaN();
}

double stableTimeStep(size_t elements, const std::function<double(size_t)>& length,
                      const std::function<const materials::BaseMaterial*(size_t)>& material, double rho) {
    const double inf = std::numeric_limits<double>::infinity();
    if (!(rho > 0)) return inf;
    double dt = inf;
    std::map<const materials::BaseMaterial*, double> speed;
    for (size_t e = 0; e < elements; ++e) {
        const materials::BaseMaterial* m = material(e);
        if (!m) continue;
        auto it = speed.find(m);
        if (it == speed.end()) it = speed.emplace(m, m->waveSpeed(rho)).first;
        if (it->second > 0) dt = std::min(dt, length(e) / it->second);
    }
    return dt;
}

EdgeRest edgeRest(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
    EdgeRest r;
    r.V.col(0) = p1 - p0;
    r.V.col(1) = p2 - p0;
    r.V.col(2) = p3 - p0;
    r.det = r.V.determinant();
    r.Vi = r.V.inverse();
    const Mat3 G = r.Vi * r.Vi.transpose();
    r.G[0] = G(0, 0);
    r.G[1] = G(1, 1);
    r.G[2] = G(2, 2);
    r.G[3] = G(0, 1);
    r.G[4] = G(1, 2);
    r.G[5] = G(0, 2);
    return r;
}

EdgeShares::EdgeShares(const Tetrahedra& tets) {
    for (const auto& t : tets)
        for (int k = 0; k < 6; ++k) {
            const int a = t[static_cast<size_t>(edgeA(k))], b = t[static_cast<size_t>(edgeB(k))];
            ++m_count[{std::min(a, b), std::max(a, b)}];
        }
}

int EdgeShares::count(int a, int b) const {
    const auto it = m_count.find({std::min(a, b), std::max(a, b)});
    return it == m_count.end() ? 0 : it->second;
}

} // namespace fascia::elements
