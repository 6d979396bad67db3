#pragma once
/// TetForceField: what every force field on linear tetrahedra needs, so that one computing its
/// stress per element (an out-of-tree force field, a prototype) writes its physics only. Derive as
///
///   class MyForceField : public fascia::elements::TetForceField<MyForceField> {
///   public:
///       void initElements();                                   // optional: after the geometry
///       double stress(const fascia::Mat3& F, fascia::Mat3& P) const;  // W (J/m^3) and P = dW/dF
///       double waveSpeed(double rho) const;                    // dilatational wave speed (m/s)
///   };
///
/// It resolves the tetrahedra ('mesh', 'tetrahedra' or the mesh source in the context) and the rest
/// positions (elements/TetMesh.h; the default dependencies, the mesh source and the state in the
/// context, are initialised first), computes the rest geometry (elements::tetRest), sorts the
/// elements into fixed blocks (ElementAssembly), and gives
///   forces    f_a = -Vol P grad N_a (F = Ds Dm^-1), on all threads, bitwise the same for any
///             thread count (docs/design.md, principle 5);
///   energy    sum_e Vol_e W_e, in element order;
///   time step min_e altitude_e / waveSpeed(rho), rho by elements::densityFor (TLED section 7).
/// Header-only and statically dispatched (CRTP): no virtual call per element (stress() is inlined
/// where its definition is visible), and the caller compiles the loop with its own OpenMP flags.
#include "fascia/elements/ElementAssembly.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/TetMesh.h"
#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

namespace fascia::elements {

template <class Derived>
class TetForceField : public core::BaseForceField {
public:
    void init() override {
        TetMesh tm = resolveTetMesh(*this, m_mesh, m_tetrahedra);
        m_tets = std::move(tm.tets);
        m_assembly.init(m_tets, tm.rest.size());    // elements sorted by lowest node, fixed blocks
        m_restGeometry = tetRest(*this, tm.rest, m_tets);  // Dm^-1, volumes, altitudes
        self().initElements();
    }
    void addForce(core::BaseMechanicalState& s, Positions& f, double) override {
        const Positions& x = s.x();
        m_assembly.addForces(m_tets, f.data()->data(), [&](size_t e, Vec3 (&fe)[4]) {
            Mat3 P;
            self().stress(deformationGradient(x, e), P);
            const Mat3 H = -m_restGeometry.volume[e] * P * m_restGeometry.DmInv[e].transpose();  // forces on nodes 1..3
            for (int k = 0; k < 3; ++k) {
                fe[k + 1] = H.col(k);
                fe[0] -= H.col(k);
            }
        });
    }
    double potentialEnergy(const core::BaseMechanicalState& s) const override {
        double W = 0;
        Mat3 P;
        for (size_t e = 0; e < m_tets.size(); ++e) W += m_restGeometry.volume[e] * self().stress(deformationGradient(s.x(), e), P);
        return W;
    }
    double stableTimeStep(const core::BaseMechanicalState&) const override {
        const double inf = std::numeric_limits<double>::infinity();
        auto* mass = node() ? node()->template findInContext<core::BaseMass>() : nullptr;
        if (!mass || m_tets.empty()) return inf;
        const auto& V = m_restGeometry.volume;
        const double rho = densityFor(*mass, std::accumulate(V.begin(), V.end(), 0.0));
        const double L = *std::min_element(m_restGeometry.altitude.begin(), m_restGeometry.altitude.end());
        return rho > 0 ? L / self().waveSpeed(rho) : inf;
    }
    size_t elementCount() const override { return m_tets.size(); }
    const Tetrahedra* tetrahedra() const override { return &m_tets; }

    core::Param<MeshData> m_mesh{this, tetMeshParam()};
    core::Param<Tetrahedra> m_tetrahedra{this, tetrahedraParam()};

protected:
    /// Called at the end of init(), with the geometry in place; override to set up the physics.
    void initElements() {}
    /// F = Ds Dm^-1 of element e at positions x.
    Mat3 deformationGradient(const Positions& x, size_t e) const {
        const auto& t = m_tets[e];
        Mat3 Ds;
        Ds << x[t[1]] - x[t[0]], x[t[2]] - x[t[0]], x[t[3]] - x[t[0]];
        return Ds * m_restGeometry.DmInv[e];
    }
    const TetRest& restGeometry() const { return m_restGeometry; }
    /// The tetrahedra, sorted by their lowest node (ElementAssembly::init): not the input order.
    const Tetrahedra& tets() const { return m_tets; }

private:
    Derived& self() { return static_cast<Derived&>(*this); }
    const Derived& self() const { return static_cast<const Derived&>(*this); }

    Tetrahedra m_tets;
    TetRest m_restGeometry;
    ElementAssembly m_assembly;
};

} // namespace fascia::elements
