#pragma once
// Helpers for the TLEDForceField tests: a bare mechanical state and mass, small structured meshes,
// materials built in code, and an independent (Eigen) evaluation of S = 2 dW/dC.
#include "fascia/tled/TLEDForceField.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include "fascia/materials/Conformance.h"
#include "fascia/materials/BuiltinMaterials.h"
#include "fascia/scene/Node.h"

#include <Eigen/Dense>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tledtest {

namespace core = fascia::core;
namespace materials = fascia::materials;
using fascia::Hexahedra;
using fascia::Mat3;
using fascia::Positions;
using fascia::Tetrahedra;
using fascia::Vec3;
using fascia::tled::TLEDForceField;
using fascia::viscoelastic::ViscoelasticProny;

/// A mechanical state whose rest positions are set from code.
struct TestState : core::BaseMechanicalState {
    void setRest(const Positions& p) {
        m_x0 = p;
        resize(p.size());
    }
};

/// A mass that only reports a density (for stable time steps).
struct TestMass : core::BaseMass {
    double rho = 1000;
    double density() const override { return rho; }
};

using ParamList = std::vector<std::pair<std::string, std::string>>;

inline void setParams(core::Component& c, const ParamList& params) {
    for (auto& [k, v] : params) {
        core::BaseParam* p = c.findParam(k);
        if (!p) throw std::runtime_error("no parameter " + k + " on " + c.className());
        p->read(v, {});
    }
}

/// Adds one of the built-in materials by class name, with parameters, and initialises it.
inline materials::BaseMaterial& addMaterial(core::Node& n, const std::string& type, const ParamList& params,
                                            const std::string& name = "material") {
    // any built-in material, from the one list (fascia/materials/BuiltinMaterials.h)
    auto made = materials::createBuiltinMaterial(type);
    if (!made) throw std::runtime_error("unknown material " + type);
    made->setName(name);
    auto* m = static_cast<materials::BaseMaterial*>(&n.addComponent(std::move(made)));
    setParams(*m, params);
    m->init();
    return *m;
}

/// Moderate parameters for every built-in material (conformance sweeps): its kExample.
inline ParamList defaultParams(const std::string& type) {
    return materials::exampleParameters(type);  // the material's own example (kExample)
}

inline const std::vector<std::string>& allMaterialTypes() {
    static const std::vector<std::string> t = materials::builtinMaterialNames();
    return t;
}

// ---- meshes ------------------------------------------------------------------------------------

inline int gridIndex(int i, int j, int k, int nx, int ny) { return i + (nx + 1) * (j + (ny + 1) * k); }

/// (nx+1)(ny+1)(nz+1) nodes of a regular grid of spacing h from the origin.
inline Positions gridPoints(int nx, int ny, int nz, double h) {
    Positions p;
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) p.emplace_back(i * h, j * h, k * h);
    return p;
}

/// The 8 corners of cell (i, j, k) in VTK hexahedron order.
inline std::array<int, 8> cellCorners(int i, int j, int k, int nx, int ny) {
    return {gridIndex(i, j, k, nx, ny),         gridIndex(i + 1, j, k, nx, ny),     gridIndex(i + 1, j + 1, k, nx, ny),
            gridIndex(i, j + 1, k, nx, ny),     gridIndex(i, j, k + 1, nx, ny),     gridIndex(i + 1, j, k + 1, nx, ny),
            gridIndex(i + 1, j + 1, k + 1, nx, ny), gridIndex(i, j + 1, k + 1, nx, ny)};
}

/// Cells with kLo <= k < kHi as hexahedra.
inline Hexahedra gridHexes(int nx, int ny, int nz, int kLo = 0, int kHi = -1) {
    Hexahedra h;
    if (kHi < 0) kHi = nz;
    for (int k = kLo; k < kHi; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) h.push_back(cellCorners(i, j, k, nx, ny));
    return h;
}

/// Cells with kLo <= k < kHi split into 6 tetrahedra around the diagonal 0-6.
inline Tetrahedra gridTets(int nx, int ny, int nz, int kLo = 0, int kHi = -1) {
    Tetrahedra t;
    if (kHi < 0) kHi = nz;
    for (int k = kLo; k < kHi; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const auto c = cellCorners(i, j, k, nx, ny);
                const int s[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
                for (auto& q : s) t.push_back({c[q[0]], c[q[1]], c[q[2]], c[q[3]]});
            }
    return t;
}

// ---- a small scene built in code ----------------------------------------------------------------

/// A root node with a state, an optional mass, materials, optional Prony series and a TLEDForceField.
struct Bench {
    core::Node root{"root"};
    TestState* state = nullptr;
    TLEDForceField* ff = nullptr;

    explicit Bench(const Positions& rest) {
        state = &root.add<TestState>("mo");
        state->setClassName("MechanicalObject");
        state->setRest(rest);
    }
    materials::BaseMaterial& material(const std::string& type, const ParamList& params, const std::string& name = "material") {
        return addMaterial(root, type, params, name);
    }
    ViscoelasticProny& prony(const std::string& alpha, const std::string& tau, const std::string& apply = "isochoric",
                             const std::string& name = "visco") {
        auto& p = root.add<ViscoelasticProny>(name);
        p.setClassName("ViscoelasticProny");
        setParams(p, {{"alpha", alpha}, {"tau", tau}, {"apply", apply}});
        p.init();
        return p;
    }
    TestMass& mass(double rho) {
        auto& m = root.add<TestMass>("mass");
        m.rho = rho;
        return m;
    }
    /// Adds the force field (not initialised: set its parameters, then call init()).
    TLEDForceField& forceField(const Tetrahedra& tets, const Hexahedra& hexes, const ParamList& params = {}) {
        ff = &root.add<TLEDForceField>("ff");
        ff->setClassName("TLEDForceField");
        ff->setLoc({"scene.xml", 12});
        if (!tets.empty()) ff->m_tetrahedra.set(tets);
        if (!hexes.empty()) ff->m_hexahedra.set(hexes);
        setParams(*ff, params);
        return *ff;
    }
    /// Positions x = F X + c for every node.
    void deform(const Mat3& F, const Vec3& c = Vec3::Zero()) {
        for (size_t i = 0; i < state->size(); ++i) state->x()[i] = F * state->x0()[i] + c;
    }
    Positions forces(double t = 0) {
        Positions f(state->size(), Vec3::Zero());
        ff->addForce(*state, f, t);
        return f;
    }
};

/// S = 2 dW/dC from the material's invariant derivatives, written with Eigen (independent of the
/// force field's code): 2 (dI1 I + dI2 (I1 I - C) + dI4 A0 + dI6 B0) + (dJiso + dJvol) J C^-1.
inline Mat3 referenceS(const materials::BaseMaterial& m, const Mat3& F, const Vec3& a0 = Vec3(0, 0, 1),
                       const Vec3& b0 = Vec3(1, 0, 0), double J0 = 0.4, Mat3* Siso = nullptr, Mat3* Svol = nullptr) {
    const materials::Invariants in = materials::conformance::invariantsOf(F, a0, b0);
    const materials::Response r = materials::conformance::evaluateOne(m, in, J0);
    const Mat3 C = F.transpose() * F;
    const Mat3 I = Mat3::Identity();
    const Mat3 JCi = in.J * C.inverse();
    const Mat3 iso = 2 * (r.dI1 * I + r.dI2 * (in.I1 * I - C) + r.dI4 * a0 * a0.transpose() + r.dI6 * b0 * b0.transpose()) +
                     r.dJiso * JCi;
    const Mat3 vol = r.dJvol * JCi;
    if (Siso) *Siso = iso;
    if (Svol) *Svol = vol;
    return iso + vol;
}

/// The largest nodal vector of ref and the largest difference |other - ref| over the nodes.
struct NodalDifference {
    double scale = 0, diff = 0;
};
inline NodalDifference nodalDifference(const Positions& ref, const Positions& other) {
    NodalDifference d;
    for (size_t i = 0; i < ref.size(); ++i) {
        d.scale = std::max(d.scale, ref[i].norm());
        d.diff = std::max(d.diff, (other[i] - ref[i]).norm());
    }
    return d;
}

/// Symmetric 3x3 from 6 components xx yy zz xy yz xz.
inline Mat3 fromVoigt(const double* s) {
    Mat3 m;
    m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    return m;
}

} // namespace tledtest
