#pragma once
#include "fascia/sim/Mechanics.h"

namespace fascia::mechanics {

/// Lumped (diagonal) mass: m_i = rho * sum(Vol_k)/4 over the tetrahedra around node i (HEML
/// section 3.3) and rho * sum(Vol_k)/8 over the hexahedra; or a total mass spread the same way.
/// Elements come from the mesh source in its context.
class LumpedMass : public core::BaseMass {
public:
    void init() override;
    double density() const override { return m_rho; }
    /// Volume of each element kind as used for the masses (m^3).
    double totalVolume() const { return m_volume; }

    core::Param<double> m_density{this, core::ParamSpec("density").unit("kg/m^3").above(0).help("mass density rho (give density or totalMass)")};
    core::Param<double> m_totalMass{this, core::ParamSpec("totalMass").unit("kg").above(0).help("total mass, spread over the nodes in proportion to their element volume (give density or totalMass)")};

private:
    double m_rho = 0, m_volume = 0;
};

/// Signed volume of a tetrahedron: det[b-a, c-a, d-a]/6 (m^3).
double tetVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// Volume of a trilinear hexahedron (VTK node order), exact 2x2x2 Gauss integration of det J.
double hexVolume(const Positions& x, const std::array<int, 8>& h);

} // namespace fascia::mechanics
