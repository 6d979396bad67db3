#pragma once
/// Rest geometry of the elements and the stable time step, shared by every element force field.
#include "fascia/base/Types.h"
#include "fascia/materials/Material.h"
#include "fascia/sim/Mechanics.h"

#include <functional>
#include <map>
#include <utility>
#include <vector>

namespace fascia::elements {

/// Signed 6 x volume of a tetrahedron: det(p1 - p0, p2 - p0, p3 - p0).
double tetSignedVolume6(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3);
/// Longest edge of a tetrahedron (m), for the degeneracy test |volume| <= 1e-12 longest^3.
double tetLongestEdge(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3);
/// Shortest altitude 3 V / (largest face area) of a tetrahedron of volume V (m): its characteristic
/// length for the stable time step (TLED section 7, HEML section 5).
double tetAltitude(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double V);
/// Characteristic length V / (largest face area) of a hexahedron (VTK node order), faces by the
/// cross product of their diagonals.
double hexCharacteristicLength(const Vec3 (&p)[8], double V);

/// Uniform-strain (Flanagan-Belytschko 1981) data of an 8-node hexahedron (VTK order) by 2x2x2
/// Gauss quadrature, exact for trilinear geometry: the signed volume V and the volume averages
/// dN[3 a + i] = (1/V) int dN_a/dX_i dV, and sumDN2 = sum_a |dN_a/dX|^2 (for the hourglass stiffness).
void hexUniformStrain(const Vec3 (&p)[8], double& V, double dN[24], double& sumDN2);
/// Natural coordinates of the 8 nodes of a hexahedron, VTK order.
extern const double kHexXi[8][3];
/// Hourglass base vectors xi eta, eta zeta, zeta xi, xi eta zeta at the nodes (Flanagan-Belytschko).
extern const double kHourglass[4][8];
/// The hourglass vectors c_q = sum_a h_qa X_a of a hexahedron at rest (h_q = kHourglass[q]), c[3 q + i]
/// (fascia/elements/Hourglass.h).
void hexHourglassVectors(const Vec3 (&p)[8], double c[12]);
/// The hourglass stiffness K = kappa (bulk + 4/3 shear modulus of m) |V| sum_a |dN_a/dX|^2 / 8 of a
/// hexahedron of volume V (hexUniformStrain's sumDN2), kappa the force field's hourglassStiffness.
double hexHourglassStiffness(double kappa, const materials::BaseMaterial& m, double absV, double sumDN2);

/// Rest data of linear tetrahedra (x = x0 + sum_k (X_k - X_0) ... through Dm^-1): the inverse rest
/// edge matrices Dm^-1 (columns X1 - X0, X2 - X0, X3 - X0), volumes and shortest altitudes.
struct TetRest {
    std::vector<Mat3> DmInv;
    std::vector<double> volume, altitude;
};
/// TetRest of every tetrahedron; fails located at owner for a node out of range or an element
/// inverted or flat at rest.
TetRest tetRest(const core::Component& owner, const Positions& X, const Tetrahedra& tets);

/// HEML's rest data of a tetrahedron (HEML Algorithm 1, Appendices A and C; fascia/elements/EdgeForm.h):
/// the rest edge matrix V (columns p1 - p0, p2 - p0, p3 - p0), its inverse Vi, det V and
/// G = Vi Vi^T as (xx yy zz xy yz xz).
struct EdgeRest {
    Mat3 V, Vi;
    double det = 0;
    double G[6] = {};
};
EdgeRest edgeRest(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3);

/// The number of tetrahedra on each mesh edge (HEML's mass-spring mode splits an edge's stiffness
/// between them, eq. (38): one spring per mesh edge in all).
class EdgeShares {
public:
    explicit EdgeShares(const Tetrahedra& tets);
    /// the tetrahedra on the edge between nodes a and b (0 for no edge)
    int count(int a, int b) const;

private:
    std::map<std::pair<int, int>, int> m_count;
};

/// The density for wave speeds: the mass's density, else its total mass over the mesh volume
/// (restVolume, m^3); NaN when neither is known. One rule for HEML and TLED.
double densityFor(const core::BaseMass& mass, double restVolume);

/// Stable time step min_e L_e / c_e (TLED section 7) over elements with characteristic length L_e
/// and material m_e (wave speed BaseMaterial::waveSpeed at rho, computed once per material).
/// Infinity when rho is not positive.
double stableTimeStep(size_t elements, const std::function<double(size_t)>& length,
                      const std::function<const materials::BaseMaterial*(size_t)>& material, double rho);

/// The worst element of a force field at the current positions x (core::BaseForceField::worstElement,
/// the order of core::worseElement): J of each tetrahedron from its signed volume, of each hexahedron
/// from the Jacobian of its trilinear map at its centre, each against the rest positions X; the
/// index counts the tetrahedra, then the hexahedra; the centroid is that of the rest element. False
/// when there is no element or a node is out of range of x or X.
bool worstElement(const Tetrahedra& tets, const Hexahedra& hexes, const Positions& X, const Positions& x,
                  core::ElementReport& out);

} // namespace fascia::elements
