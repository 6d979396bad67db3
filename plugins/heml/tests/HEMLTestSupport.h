#pragma once
// Scenes built in code for the HEMLForceField tests (the mechanics plugin is not needed): a bare
// mechanical state and mass, jittered cube meshes, every built-in material.
#include "fascia/heml/HEMLForceField.h"
#include "fascia/materials/BuiltinMaterials.h"
#include "fascia/scene/Node.h"

#include <memory>
#include <random>
#include <string>

namespace hemltest {

using namespace fascia;

struct TestState : core::BaseMechanicalState {
    void setRest(const Positions& X) {
        m_x0 = X;
        resize(X.size());
    }
};

struct TestMass : core::BaseMass {
    double rho = 1000;
    double density() const override { return rho; }
    void setMasses(std::vector<double> m) { m_masses = std::move(m); }
};

/// A box of nx*ny*nz cubes of side h, each split into 6 tetrahedra along its main diagonal
/// (conforming; half of them negatively oriented). Interior nodes jittered by `jitter` h.
inline MeshData cubeMesh(int nx, int ny, int nz, double h = 0.01, double jitter = 0.15, unsigned seed = 7) {
    MeshData m;
    auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                Vec3 p(i * h, j * h, k * h);
                const bool interior = i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz;
                if (interior) p += jitter * h * Vec3(u(rng), u(rng), u(rng));
                m.points.push_back(p);
            }
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                for (const auto& p : perms) {
                    int c[3] = {0, 0, 0};
                    std::array<int, 4> t;
                    t[0] = id(i, j, k);
                    for (int s = 0; s < 3; ++s) {
                        c[p[s]] = 1;
                        t[s + 1] = id(i + c[0], j + c[1], k + c[2]);
                    }
                    m.tetrahedra.push_back(t);
                    m.tetrahedronGroup.push_back(i < nx / 2 ? 1 : 2);
                }
    m.groupNames = {{1, "left"}, {2, "right"}};
    return m;
}

/// Every built-in material, from the one list (fascia/materials/BuiltinMaterials.h).
inline const std::vector<std::string> kMaterials = materials::builtinMaterialNames();

/// Parameters of the HEML tests where they differ from the material's own example (kExample).
inline std::vector<std::pair<std::string, std::string>> hemlParams(const std::string& type) {
    if (type == "StVenantKirchhoff") return {{"youngModulus", "3000"}, {"poissonRatio", "0.3"}};
    if (type == "IncompressibleMooneyRivlin") return {{"C1", "400"}, {"C2", "150"}};
    if (type == "CompressibleNeoHookean") return {{"mu", "1000"}, {"lambda", "4000"}};
    if (type == "CompressibleMooneyRivlin") return {{"C1", "400"}, {"C2", "150"}, {"kappa", "20000"}};
    if (type == "TransverselyIsotropic") return {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "2000"}, {"direction", "1 1 0.5"}};
    if (type == "Orthotropic")
        return {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "2000"}, {"eta2", "700"}, {"direction", "1 1 0"}, {"direction2", "-1 1 0"}};
    return materials::exampleParameters(type);
}

/// Adds a built-in material to a node (not initialised).
inline materials::BaseMaterial& addMaterial(core::Node& n, const std::string& type, const std::string& name) {
    auto made = materials::createBuiltinMaterial(type);
    if (!made) throw std::runtime_error("unknown material " + type);
    made->setName(name);
    auto& m = static_cast<materials::BaseMaterial&>(n.addComponent(std::move(made)));
    for (const auto& [k, v] : hemlParams(type)) m.findParam(k)->read(v, {});
    return m;
}

/// A node with a state, a mass, materials and a force field, initialised in dependency order.
struct Scene {
    core::Node root{"root"};
    TestState* state = nullptr;
    TestMass* mass = nullptr;
    heml::HEMLForceField* ff = nullptr;

    explicit Scene(const MeshData& mesh) {
        state = &root.add<TestState>("mo");
        state->setRest(mesh.points);
        mass = &root.add<TestMass>("mass");
        ff = &root.add<heml::HEMLForceField>("ff");
        ff->m_mesh.set(mesh);
    }
    /// Initialises every component (materials first, the force field last).
    void init() {
        for (auto& c : root.components())
            if (c.get() != ff) c->init();
        ff->init();
    }
    /// Forces at time t (s): a new time advances the viscous history (viscoelastic/HistoryClock.h).
    Positions forces(double t = 0.0) {
        Positions f(state->size(), Vec3::Zero());
        ff->addForce(*state, f, t);
        return f;
    }
};

inline double maxNorm(const Positions& f) {
    double m = 0;
    for (const auto& v : f) m = std::max(m, v.norm());
    return m;
}

} // namespace hemltest
