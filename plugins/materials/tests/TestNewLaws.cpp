// The laws beyond the papers' (HolzapfelGasserOgden, ArrudaBoyce, UncoupledMooneyRivlin, Gent) and
// the libm-free exponential they need: fastExp against std::exp; law-level conformance; energies
// against W computed here from F with Eigen and std:: functions; closed-form stresses (principal
// stretches, simple shear, pure dilatation) at law level and through TLEDForceField and
// HEMLForceField; the conformance harness through both force fields; moduli and stable time steps;
// located parameter errors; the registry's descriptions (what --list and --describe print).
#include "fascia/heml/HEMLForceField.h"
#include "fascia/tled/TLEDForceField.h"

#include "fascia/materials/ArrudaBoyce.h"
#include "fascia/materials/Conformance.h"
#include "fascia/materials/FastExp.h"
#include "fascia/materials/Gent.h"
#include "fascia/materials/HolzapfelGasserOgden.h"
#include "fascia/materials/NeoHookean.h"
#include "fascia/materials/UncoupledMooneyRivlin.h"
#include "fascia/plugin/PluginManager.h"
#include "fascia/plugin/Registry.h"
#include "fascia/scene/Node.h"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace fascia;
namespace conf = fascia::materials::conformance;
using materials::BaseMaterial;
using materials::Invariants;
using materials::Response;

namespace {

// ---- materials built as a scene would build them (parameters read from text) --------------------

using ParamList = std::vector<std::pair<std::string, std::string>>;

// the parameter sets the tests use; "HGO2": two off-axis families with dispersion, "HGO1": one
// family with k2 = 0 (quadratic fibres), "HGO0": HGO2 without fibres (k1 = 0), "HGOx": HGO2 with
// the fibres along x and y (for the principal-stretch formula)
const std::map<std::string, std::pair<std::string, ParamList>>& variants() {
    static const std::map<std::string, std::pair<std::string, ParamList>> v = {
        {"HGO2", {"HolzapfelGasserOgden", {{"mu", "1000"}, {"k1", "3000"}, {"k2", "4"}, {"dispersion", "0.1"},
                                           {"bulkModulus", "20000"}, {"direction", "1 0.2 0.3"}, {"direction2", "-0.2 1 0.4"}}}},
        {"HGO1", {"HolzapfelGasserOgden", {{"mu", "800"}, {"k1", "5000"}, {"k2", "0"}, {"bulkModulus", "15000"}, {"direction", "0.3 -0.4 1"}}}},
        {"HGO0", {"HolzapfelGasserOgden", {{"mu", "1000"}, {"k1", "0"}, {"k2", "4"}, {"dispersion", "0.1"},
                                           {"bulkModulus", "20000"}, {"direction", "1 0.2 0.3"}, {"direction2", "-0.2 1 0.4"}}}},
        {"HGOx", {"HolzapfelGasserOgden", {{"mu", "1000"}, {"k1", "3000"}, {"k2", "4"}, {"dispersion", "0.1"},
                                           {"bulkModulus", "20000"}, {"direction", "2 0 0"}, {"direction2", "0 1 0"}}}},
        {"AB", {"ArrudaBoyce", {{"mu", "1000"}, {"lambdaM", "2"}, {"kappa", "20000"}}}},
        {"UMR", {"UncoupledMooneyRivlin", {{"c1", "400"}, {"c2", "150"}, {"k", "20000"}}}},
        {"GENT", {"Gent", {{"mu", "1000"}, {"Jm", "2"}, {"k", "20000"}}}},
    };
    return v;
}

const char* const kVariants[] = {"HGO2", "HGO1", "AB", "UMR", "GENT"};

void readParams(core::Component& c, const ParamList& params, int line = 1) {
    for (const auto& [k, v] : params) {
        core::BaseParam* p = c.findParam(k);
        if (!p) throw std::runtime_error("no parameter " + k + " on " + c.className());
        p->read(v, {"scene.xml", line});
    }
}

BaseMaterial& addLaw(core::Node& n, const std::string& type, const std::string& name = "material") {
    BaseMaterial* m = nullptr;
    if (type == "HolzapfelGasserOgden") m = &n.add<materials::HolzapfelGasserOgden>(name);
    else if (type == "ArrudaBoyce") m = &n.add<materials::ArrudaBoyce>(name);
    else if (type == "UncoupledMooneyRivlin") m = &n.add<materials::UncoupledMooneyRivlin>(name);
    else if (type == "Gent") m = &n.add<materials::Gent>(name);
    else if (type == "NeoHookean") m = &n.add<materials::NeoHookean>(name);
    else throw std::runtime_error("unknown law " + type);
    m->setClassName(type);
    m->setLoc({"scene.xml", 1});
    return *m;
}

/// A material of the given type and parameters, added to n and initialised.
BaseMaterial& addMaterial(core::Node& n, const std::string& type, const ParamList& params, const std::string& name) {
    BaseMaterial& m = addLaw(n, type, name);
    readParams(m, params);
    m.init();
    return m;
}

/// A material of one of the variants, added to n and initialised.
BaseMaterial& addVariant(core::Node& n, const std::string& variant, const std::string& name = "material") {
    const auto& [type, params] = variants().at(variant);
    return addMaterial(n, type, params, name);
}

double param(const std::string& variant, const std::string& name, double fallback = 0) {
    for (const auto& [k, v] : variants().at(variant).second)
        if (k == name) return std::stod(v);
    return fallback;
}

Vec3 vecParam(const std::string& variant, const std::string& name) {
    for (const auto& [k, v] : variants().at(variant).second)
        if (k == name) {
            std::istringstream is(v);
            Vec3 d;
            is >> d[0] >> d[1] >> d[2];
            return d.normalized();
        }
    return Vec3::Zero();
}

bool hasParam(const std::string& variant, const std::string& name) {
    for (const auto& kv : variants().at(variant).second)
        if (kv.first == name) return true;
    return false;
}

Vec3 dirOf(const BaseMaterial& m, int k) {
    const Vec3* d = m.fibreDirection(k);
    return d ? *d : (k == 0 ? Vec3(0, 0, 1) : Vec3(1, 0, 0));
}

double energyOfF(const BaseMaterial& m, const Mat3& F, double J0 = 0.4) {
    return conf::evaluateOne(m, conf::invariantsOf(F, dirOf(m, 0), dirOf(m, 1)), J0).W;
}

// deformation gradients: general, compressive, large stretch, two that stretch the HGO2 fibre a0
// and compress b0 (or the reverse), and one below J0 (the last)
Mat3 testF(int k) {
    switch (k) {
    case 0: return (Mat3() << 1.2, 0.1, 0.0, -0.05, 0.9, 0.2, 0.03, 0.0, 1.1).finished();
    case 1: return (Mat3() << 0.8, 0.3, 0.1, 0.0, 0.7, -0.1, 0.2, 0.05, 0.9).finished();
    case 2: return (Mat3() << 1.6, 0.0, 0.0, 0.4, 1.3, 0.0, 0.0, -0.2, 1.4).finished();
    case 3: return (Mat3() << 1.25, 0.05, 0.1, 0.0, 0.85, 0.0, 0.05, 0.0, 0.95).finished();
    case 4: return (Mat3() << 0.85, 0.1, 0.0, 0.0, 1.3, 0.1, 0.0, -0.05, 1.05).finished();
    default: return (Mat3() << 0.6, 0.1, 0.0, 0.0, 0.55, 0.05, 0.0, 0.0, 0.6).finished();  // J ~ 0.2 < J0
    }
}
constexpr int kTestF = 6;

// ---- energies written from F, independent of the laws' code ------------------------------------

struct Kinematics {
    double J, I1b, I2b;
    Mat3 Cb;  // J^(-2/3) C
};
Kinematics kinematics(const Mat3& F) {
    Kinematics k;
    k.J = F.determinant();
    k.Cb = std::pow(k.J, -2.0 / 3.0) * (F.transpose() * F);
    k.I1b = k.Cb.trace();
    k.I2b = 0.5 * (k.I1b * k.I1b - (k.Cb * k.Cb).trace());
    return k;
}

// HGO fibre strain E_i of one family (unit direction a) and its energy
double hgoFibreStrain(const Kinematics& k, const Vec3& a, double kap) {
    return kap * (k.I1b - 3) + (1 - 3 * kap) * (a.dot(k.Cb * a) - 1);
}
double hgoFibreEnergy(double E, double k1, double k2) {
    if (!(E > 0)) return 0;  // fibres in tension only
    return k2 > 0 ? k1 / (2 * k2) * (std::exp(k2 * E * E) - 1) : 0.5 * k1 * E * E;
}

double directEnergy(const std::string& variant, const Mat3& F) {
    const Kinematics k = kinematics(F);
    const double lnJ = std::log(k.J);
    const std::string& type = variants().at(variant).first;
    if (type == "HolzapfelGasserOgden") {
        const double kap = param(variant, "dispersion"), k1 = param(variant, "k1"), k2 = param(variant, "k2");
        double W = 0.5 * param(variant, "mu") * (k.I1b - 3) + 0.5 * param(variant, "bulkModulus") * lnJ * lnJ;
        W += hgoFibreEnergy(hgoFibreStrain(k, vecParam(variant, "direction"), kap), k1, k2);
        if (hasParam(variant, "direction2"))
            W += hgoFibreEnergy(hgoFibreStrain(k, vecParam(variant, "direction2"), kap), k1, k2);
        return W;
    }
    if (type == "ArrudaBoyce") {
        const double C[5] = {1.0 / 2, 1.0 / 20, 11.0 / 1050, 19.0 / 7000, 519.0 / 673750};
        const double mu = param(variant, "mu"), lm = param(variant, "lambdaM"), kap = param(variant, "kappa");
        double W = 0.5 * kap * (k.J - 1) * (k.J - 1);
        for (int i = 1; i <= 5; ++i) W += mu * C[i - 1] / std::pow(lm, 2 * i - 2) * (std::pow(k.I1b, i) - std::pow(3.0, i));
        return W;
    }
    if (type == "Gent") {
        const double mu = param(variant, "mu"), Jm = param(variant, "Jm");
        return -0.5 * mu * Jm * std::log(1 - (k.I1b - 3) / Jm) + 0.5 * param(variant, "k") * lnJ * lnJ;
    }
    return param(variant, "c1") * (k.I1b - 3) + param(variant, "c2") * (k.I2b - 3) + 0.5 * param(variant, "k") * lnJ * lnJ;
}

// ---- stresses from the law's response (Material.h), and closed forms --------------------------

/// Cauchy stress J^-1 F S F^T with S = 2 [dI1 I + dI2 (I1 I - C) + dI4 A0 + dI6 B0] + J dW/dJ C^-1.
Mat3 lawCauchy(const BaseMaterial& m, const Mat3& F) {
    const Vec3 a = dirOf(m, 0), b = dirOf(m, 1);
    const Invariants in = conf::invariantsOf(F, a, b);
    const Response r = conf::evaluateOne(m, in, 0.4);
    const Mat3 C = F.transpose() * F, I = Mat3::Identity();
    const Mat3 S = 2 * (r.dI1 * I + r.dI2 * (in.I1 * I - C) + r.dI4 * a * a.transpose() + r.dI6 * b * b.transpose()) +
                   in.J * (r.dJiso + r.dJvol) * C.inverse();
    return F * S * F.transpose() / in.J;
}

Mat3 dev(const Mat3& A) { return A - A.trace() / 3 * Mat3::Identity(); }

/// HGO under F = diag(l), fibres along e1 (a0) and e2 (b0, when two), by the principal-stretch
/// formula of the isochoric/volumetric split:
///   sigma_j = (lb_j dW/dlb_j - 1/3 sum_m lb_m dW/dlb_m) / J + dU/dJ,  lb_j = J^(-1/3) l_j,
///   lb_j dW/dlb_j = mu lb_j^2 + 2 kappa (g4 + g6) lb_j^2 + 2 (1 - 3 kappa)(g4 [j = 1] + g6 [j = 2]) lb_j^2,
/// g_i = k1 <E_i> exp(k2 <E_i>^2), dU/dJ = K ln J / J.
Mat3 hgoPrincipalCauchy(const Vec3& l, double mu, double k1, double k2, double kap, double K, bool two, double* E4out = nullptr,
                        double* E6out = nullptr) {
    const double J = l.prod();
    const Vec3 lb = l * std::pow(J, -1.0 / 3.0);
    const Vec3 lb2 = lb.cwiseProduct(lb);
    const double I1b = lb2.sum();
    const double E4 = kap * (I1b - 3) + (1 - 3 * kap) * (lb2[0] - 1);
    const double E6 = kap * (I1b - 3) + (1 - 3 * kap) * (lb2[1] - 1);
    if (E4out) *E4out = E4;
    if (E6out) *E6out = E6;
    const double g4 = E4 > 0 ? k1 * E4 * std::exp(k2 * E4 * E4) : 0.0;
    const double g6 = two && E6 > 0 ? k1 * E6 * std::exp(k2 * E6 * E6) : 0.0;
    Vec3 d;
    for (int j = 0; j < 3; ++j)
        d[j] = mu * lb2[j] + 2 * kap * (g4 + g6) * lb2[j] + 2 * (1 - 3 * kap) * ((j == 0 ? g4 : 0) + (j == 1 ? g6 : 0)) * lb2[j];
    const double mean = d.sum() / 3;
    Mat3 s = Mat3::Zero();
    for (int j = 0; j < 3; ++j) s(j, j) = (d[j] - mean) / J + K * std::log(J) / J;
    return s;
}

/// Arruda-Boyce: sigma = 2/J W1(I1bar) dev(Bbar) + kappa (J - 1) I, W1 = mu sum_i i C_i I1bar^(i-1) / lm^(2i-2).
Mat3 abCauchy(const Mat3& F, double mu, double lm, double kap) {
    const double C[5] = {1.0 / 2, 1.0 / 20, 11.0 / 1050, 19.0 / 7000, 519.0 / 673750};
    const double J = F.determinant();
    const Mat3 Bb = std::pow(J, -2.0 / 3.0) * F * F.transpose();
    double W1 = 0;
    for (int i = 1; i <= 5; ++i) W1 += mu * i * C[i - 1] * std::pow(Bb.trace(), i - 1) / std::pow(lm, 2 * i - 2);
    return 2 / J * W1 * dev(Bb) + kap * (J - 1) * Mat3::Identity();
}

/// Mooney-Rivlin with the split: sigma = 2/J dev[(c1 + c2 I1bar) Bbar - c2 Bbar^2] + k ln J / J I.
Mat3 umrCauchy(const Mat3& F, double c1, double c2, double k) {
    const double J = F.determinant();
    const Mat3 Bb = std::pow(J, -2.0 / 3.0) * F * F.transpose();
    return 2 / J * dev((c1 + c2 * Bb.trace()) * Bb - c2 * Bb * Bb) + k * std::log(J) / J * Mat3::Identity();
}

/// Gent (Gent 1996): sigma = 2/J w dev(Bbar) + k ln J / J I, w = dW/dI1bar = mu/2 / (1 - (I1bar - 3)/Jm).
Mat3 gentCauchy(const Mat3& F, double mu, double Jm, double k) {
    const double J = F.determinant();
    const Mat3 Bb = std::pow(J, -2.0 / 3.0) * F * F.transpose();
    const double w = 0.5 * mu / (1 - (Bb.trace() - 3) / Jm);
    return 2 / J * w * dev(Bb) + k * std::log(J) / J * Mat3::Identity();
}

double vonMises(const Mat3& s) {
    const Mat3 d = dev(s);
    return std::sqrt(1.5 * (d.array() * d.array()).sum());
}

Mat3 simpleShear(double g) {
    Mat3 F = Mat3::Identity();
    F(0, 1) = g;
    return F;
}

// ---- scenes built in code for the force fields --------------------------------------------------

struct TestState : core::BaseMechanicalState {
    void setRest(const Positions& X) {
        x0() = X;
        resize(X.size());
    }
};

struct TestMass : core::BaseMass {
    double rho = 1000;
    double density() const override { return rho; }
};

// a material that is not a Material<Law>: the force fields' batched (generic) path
struct Wrapped : BaseMaterial {
    const BaseMaterial* inner = nullptr;
    unsigned uses() const override { return inner->uses(); }
    void evaluate(const Invariants* in, Response* out, size_t n, double J0) const override { inner->evaluate(in, out, n, J0); }
    double shearModulus() const override { return inner->shearModulus(); }
    double bulkModulus() const override { return inner->bulkModulus(); }
    double waveSpeed(double rho) const override { return inner->waveSpeed(rho); }
    const Vec3* fibreDirection(int w) const override { return inner->fibreDirection(w); }
    bool stressFreeAtRest() const override { return inner->stressFreeAtRest(); }
};

/// A box of nx x ny x nz cells of side h: 6 positively oriented tetrahedra per cell (Kuhn split)
/// or one hexahedron (VTK order); interior nodes jittered by jitter * h.
MeshData boxMesh(int nx, int ny, int nz, bool hexes, double h = 0.01, double jitter = 0.0, unsigned seed = 5) {
    MeshData m;
    auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                Vec3 p(i * h, j * h, k * h);
                if (i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz) p += jitter * h * Vec3(u(rng), u(rng), u(rng));
                m.points.push_back(p);
            }
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (hexes) {
                    m.hexahedra.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                                           id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
                    continue;
                }
                for (const auto& p : perms) {
                    int c[3] = {0, 0, 0};
                    std::array<int, 4> t;
                    t[0] = id(i, j, k);
                    for (int s = 0; s < 3; ++s) {
                        c[p[s]] = 1;
                        t[s + 1] = id(i + c[0], j + c[1], k + c[2]);
                    }
                    Mat3 V;
                    for (int s = 0; s < 3; ++s) V.col(s) = m.points[t[s + 1]] - m.points[t[0]];
                    if (V.determinant() < 0) std::swap(t[2], t[3]);
                    m.tetrahedra.push_back(t);
                }
            }
    return m;
}

/// A node with a state, a mass, a material (one of the variants, optionally behind Wrapped) and a
/// force field FF (HEMLForceField or TLEDForceField) reading the mesh through its 'mesh' parameter.
template <class FF>
struct Rig {
    core::Node root{"root"};
    TestState* state = nullptr;
    TestMass* mass = nullptr;
    BaseMaterial* material = nullptr;
    FF* ff = nullptr;

    Rig(const MeshData& mesh, const std::string& variant, bool generic = false)
        : Rig(mesh, variants().at(variant).first, variants().at(variant).second, generic) {}
    Rig(const MeshData& mesh, const std::string& type, const ParamList& params, bool generic = false) {
        state = &root.add<TestState>("mo");
        state->setClassName("MechanicalObject");
        state->setRest(mesh.points);
        mass = &root.add<TestMass>("mass");
        material = &addMaterial(root, type, params, "mat");
        ff = &root.add<FF>("ff");
        ff->setLoc({"scene.xml", 20});
        auto* meshParam = dynamic_cast<core::Param<MeshData>*>(ff->findParam("mesh"));
        REQUIRE(meshParam);
        meshParam->set(mesh);
        if (generic) {
            auto& w = root.add<Wrapped>("wrapped");
            w.inner = material;
            ff->m_material.set(&w);
        } else {
            ff->m_material.set(material);
        }
        ff->init();
    }
    void deform(const Mat3& F) {
        for (size_t i = 0; i < state->size(); ++i) state->x()[i] = F * state->x0()[i];
    }
    /// The cell field `name` of element e (components in the order xx yy zz xy yz xz for tensors).
    std::vector<double> cell(const std::string& name, size_t e) {
        std::vector<core::CellField> cells;
        ff->cellData(*state, cells);
        for (const auto& c : cells)
            if (c.name == name)
                return std::vector<double>(c.values.begin() + long(e * c.components), c.values.begin() + long((e + 1) * c.components));
        FAIL("no cell field " << name);
        return {};
    }
};

Mat3 fromVoigt(const std::vector<double>& s) {
    Mat3 m;
    m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    return m;
}

} // namespace

// ---- the exponential ------------------------------------------------------------------------------

TEST_CASE("fastExp matches std::exp to about an ulp from -700 to 700", "[fastExp]") {
    double worst = 0;
    for (double x = -700; x < 700; x += 0.01373) worst = std::max(worst, std::abs(materials::fastExp(x) - std::exp(x)) / std::exp(x));
    for (double x = -1; x < 1; x += 1.37e-4) worst = std::max(worst, std::abs(materials::fastExp(x) - std::exp(x)) / std::exp(x));
    INFO("worst relative error " << worst);
    CHECK(worst < 3e-16);
    CHECK(materials::fastExp(0.0) == 1.0);
    CHECK(materials::fastExp(1.0) == Approx(std::exp(1.0)).epsilon(3e-16));
    // clamped instead of overflowing
    CHECK(std::isfinite(materials::fastExp(1000.0)));
    CHECK(materials::fastExp(1000.0) == Approx(std::exp(708.0)).epsilon(1e-15));
}

TEST_CASE("fastExprel is (e^x - 1)/x without cancellation near zero", "[fastExp]") {
    double worst = 0;
    for (double x = -40; x < 40; x += 0.00731) {
        const double ref = x == 0 ? 1.0 : std::expm1(x) / x;
        worst = std::max(worst, std::abs(materials::fastExprel(x) - ref) / ref);
    }
    for (double x = 1e-300; x < 1; x *= 1.7) {
        worst = std::max(worst, std::abs(materials::fastExprel(x) - std::expm1(x) / x) / (std::expm1(x) / x));
        worst = std::max(worst, std::abs(materials::fastExprel(-x) - std::expm1(-x) / -x) / (std::expm1(-x) / -x));
    }
    INFO("worst relative error " << worst);
    CHECK(worst < 1e-15);
    CHECK(materials::fastExprel(0.0) == 1.0);
}

// ---- law level ------------------------------------------------------------------------------------

TEST_CASE("every derivative of the new laws matches central differences of their energy", "[HolzapfelGasserOgden][ArrudaBoyce][UncoupledMooneyRivlin]") {
    const std::string variant = GENERATE(from_range(std::begin(kVariants), std::end(kVariants)));
    const int k = GENERATE(range(0, kTestF));
    core::Node root("root");
    const BaseMaterial& m = addVariant(root, variant);
    const Invariants in = conf::invariantsOf(testF(k), dirOf(m, 0), dirOf(m, 1));
    const auto rep = conf::checkLawDerivatives(m, in, 0.4);
    INFO(variant << " F#" << k << " J = " << in.J << " worst " << rep.worst << ": " << rep.analytic << " vs " << rep.numeric);
    CHECK(rep.maxRelError < 1e-7);
}

TEST_CASE("the new laws are stress-free at rest, continuous across J0 and finite through inversion", "[HolzapfelGasserOgden][ArrudaBoyce][UncoupledMooneyRivlin]") {
    const std::string variant = GENERATE(from_range(std::begin(kVariants), std::end(kVariants)));
    core::Node root("root");
    const BaseMaterial& m = addVariant(root, variant);
    INFO(variant);
    CHECK(m.stressFreeAtRest());
    CHECK(conf::restStressResidual(m) < 1e-14);
    const Invariants in = conf::invariantsOf(testF(1), dirOf(m, 0), dirOf(m, 1));
    CHECK(conf::energyJumpAtJ0(m, in, 0.4) < 1e-9);
    double prev = 0;
    for (double J : {0.6, 0.4, 0.2, 0.0, -0.3}) {
        Invariants c;
        c.J = J;
        const Response r = conf::evaluateOne(m, c, 0.4);
        CAPTURE(J);
        CHECK(std::isfinite(r.W));
        CHECK(r.dJvol < 0);  // compression resisted, ever harder
        if (J < 0.6) CHECK(r.dJvol < prev);
        prev = r.dJvol;
    }
}

TEST_CASE("the new laws' energies equal W computed from F with Eigen and std functions", "[HolzapfelGasserOgden][ArrudaBoyce][UncoupledMooneyRivlin]") {
    const std::string variant = GENERATE(from_range(std::begin(kVariants), std::end(kVariants)));
    core::Node root("root");
    const BaseMaterial& m = addVariant(root, variant);
    int fibresOn = 0, fibresOff = 0;
    for (int k = 0; k + 1 < kTestF; ++k) {  // J > J0 (below it the law continues along a tangent)
        const Mat3 F = testF(k);
        CAPTURE(variant, k);
        CHECK(energyOfF(m, F) == Approx(directEnergy(variant, F)).epsilon(1e-12));
        if (variant == "HGO2") {
            const Kinematics kin = kinematics(F);
            for (const char* d : {"direction", "direction2"}) {
                const double E = hgoFibreStrain(kin, vecParam(variant, d), param(variant, "dispersion"));
                (E > 0 ? fibresOn : fibresOff) += 1;
            }
        }
    }
    if (variant == "HGO2") {
        // the deformations load each side of the tension switch
        CHECK(fibresOn >= 3);
        CHECK(fibresOff >= 3);
    }
}

TEST_CASE("P = F S from the new laws' derivatives is the finite-difference derivative of W(F)", "[HolzapfelGasserOgden][ArrudaBoyce][UncoupledMooneyRivlin]") {
    const std::string variant = GENERATE(from_range(std::begin(kVariants), std::end(kVariants)));
    const int k = GENERATE(range(0, kTestF - 1));
    core::Node root("root");
    const BaseMaterial& m = addVariant(root, variant);
    const Mat3 F = testF(k);
    const Mat3 P = lawCauchy(m, F) * F.determinant() * F.inverse().transpose();
    Mat3 Pfd;
    const double h = 1e-6;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            Mat3 Fp = F, Fm = F;
            Fp(i, j) += h;
            Fm(i, j) -= h;
            Pfd(i, j) = (directEnergy(variant, Fp) - directEnergy(variant, Fm)) / (2 * h);
        }
    INFO(variant << " F#" << k << "\nP =\n" << P << "\nfd =\n" << Pfd);
    CHECK((P - Pfd).norm() < 1e-7 * P.norm());
}

// ---- closed forms ---------------------------------------------------------------------------------

TEST_CASE("HGO fibres carry stress in tension only, as the principal-stretch formula gives", "[HolzapfelGasserOgden]") {
    const double mu = 1000, k1 = 3000, k2 = 4, kap = 0.1, K = 20000;
    core::Node root("root");
    const BaseMaterial& hgo = addVariant(root, "HGOx", "hgo");
    // the matrix alone: no fibre stiffness, one family, no dispersion
    const BaseMaterial& matrix =
        addMaterial(root, "HolzapfelGasserOgden", {{"mu", "1000"}, {"k1", "0"}, {"k2", "4"}, {"bulkModulus", "20000"}}, "matrix");

    SECTION("a0 stretched, b0 compressed: only the first family pulls") {
        const Vec3 l(1.25, 0.92, 0.95);
        double E4, E6;
        const Mat3 ref = hgoPrincipalCauchy(l, mu, k1, k2, kap, K, true, &E4, &E6);
        REQUIRE(E4 > 0.1);
        REQUIRE(E6 < -0.01);
        const Mat3 s = lawCauchy(hgo, l.asDiagonal());
        INFO("sigma =\n" << s << "\nclosed form =\n" << ref);
        CHECK((s - ref).norm() < 1e-10 * ref.norm());
        // the fibre adds a tension along a0 on top of the matrix
        CHECK(s(0, 0) - lawCauchy(matrix, l.asDiagonal())(0, 0) > 0.2 * mu);
    }
    SECTION("both families compressed: exactly the matrix") {
        const Vec3 l(0.93, 0.9, 1.2);
        double E4, E6;
        const Mat3 ref = hgoPrincipalCauchy(l, mu, k1, k2, kap, K, true, &E4, &E6);
        REQUIRE(E4 < 0);
        REQUIRE(E6 < 0);
        const Mat3 s = lawCauchy(hgo, l.asDiagonal());
        CHECK((s - ref).norm() < 1e-10 * ref.norm());
        CHECK(s == lawCauchy(matrix, l.asDiagonal()));
        CHECK(energyOfF(hgo, l.asDiagonal()) == energyOfF(matrix, l.asDiagonal()));
    }
    SECTION("dispersion can switch a compressed direction on through I1bar") {
        // lateral stretch: I4bar < 1 but kappa (I1bar - 3) wins for kappa near 1/3
        const BaseMaterial& disp = addMaterial(root, "HolzapfelGasserOgden",
                                               {{"mu", "1000"}, {"k1", "3000"}, {"k2", "4"}, {"dispersion", "0.3"},
                                                {"bulkModulus", "20000"}, {"direction", "1 0 0"}},
                                               "disp");
        const Vec3 l(0.98, 1.4, 0.75);
        double E4;
        const Mat3 ref = hgoPrincipalCauchy(l, mu, k1, k2, 0.3, K, false, &E4);
        REQUIRE(E4 > 0);
        REQUIRE(l[0] * std::pow(l.prod(), -1.0 / 3.0) < 1.0);
        CHECK((lawCauchy(disp, l.asDiagonal()) - ref).norm() < 1e-10 * ref.norm());
    }
}

TEST_CASE("Arruda-Boyce in simple shear has the closed-form stress and the series' small-strain shear modulus", "[ArrudaBoyce]") {
    const double mu = 1000, lm = 2, kap = 20000;
    core::Node root("root");
    const BaseMaterial& m = addVariant(root, "AB");
    // mu0 = 2 dW/dI1bar at 3 = mu sum_i 2 i C_i 3^(i-1) / lm^(2i-2) = mu (1 + 3/(5 lm^2) + 99/(175 lm^4) + ...)
    const double C[5] = {1.0 / 2, 1.0 / 20, 11.0 / 1050, 19.0 / 7000, 519.0 / 673750};
    double mu0 = 0;
    for (int i = 1; i <= 5; ++i) mu0 += mu * 2 * i * C[i - 1] * std::pow(3.0, i - 1) / std::pow(lm, 2 * i - 2);
    CHECK(mu0 == Approx(mu * (1 + 3 / (5 * lm * lm) + 99 / (175 * std::pow(lm, 4)) + 513 / (875 * std::pow(lm, 6)) +
                              42039 / (67375 * std::pow(lm, 8))))
                     .epsilon(1e-14));
    CHECK(m.shearModulus() == Approx(mu0).epsilon(1e-14));
    CHECK(m.bulkModulus() == kap);

    SECTION("finite shear: sigma = 2 W1(3 + gamma^2) dev(B)") {
        for (double g : {0.3, 0.8}) {
            const Mat3 F = simpleShear(g);
            const Mat3 ref = abCauchy(F, mu, lm, kap);
            CAPTURE(g);
            CHECK((lawCauchy(m, F) - ref).norm() < 1e-10 * ref.norm());
            CHECK(ref(0, 1) > mu0 * g);  // stiffer than linear: the chains stretch
        }
        const Mat3 F = testF(0);  // compressible, general
        CHECK((lawCauchy(m, F) - abCauchy(F, mu, lm, kap)).norm() < 1e-10 * abCauchy(F, mu, lm, kap).norm());
    }
    SECTION("small shear: sigma_xy / gamma tends to mu0") {
        const double g = 1e-5;
        CHECK(lawCauchy(m, simpleShear(g))(0, 1) / g == Approx(mu0).epsilon(1e-8));
    }
}

TEST_CASE("uncoupled Mooney-Rivlin: k ln J / J in pure dilatation and 2 (c1 + c2) gamma in simple shear", "[UncoupledMooneyRivlin]") {
    const double c1 = 400, c2 = 150, k = 20000;
    core::Node root("root");
    const BaseMaterial& m = addVariant(root, "UMR");
    CHECK(m.shearModulus() == 2 * (c1 + c2));
    CHECK(m.bulkModulus() == k);
    SECTION("pure dilatation: the isochoric part gives no stress") {
        for (double l : {0.8, 1.1}) {
            const double J = l * l * l;
            const Mat3 s = lawCauchy(m, l * Mat3::Identity());
            CAPTURE(l);
            CHECK((s - k * std::log(J) / J * Mat3::Identity()).norm() < 1e-10 * k * std::abs(std::log(J)));
        }
    }
    SECTION("simple shear") {
        for (double g : {0.2, 1.0}) {
            const Mat3 s = lawCauchy(m, simpleShear(g));
            CAPTURE(g);
            CHECK(s(0, 1) == Approx(2 * (c1 + c2) * g).epsilon(1e-12));
            CHECK(s(0, 0) - s(1, 1) == Approx(2 * (c1 + c2) * g * g).epsilon(1e-12));
            CHECK(s(1, 1) - s(2, 2) == Approx(-2 * c2 * g * g).epsilon(1e-12));
            CHECK((s - umrCauchy(simpleShear(g), c1, c2, k)).norm() < 1e-10 * s.norm());
        }
    }
    SECTION("a general compressible deformation") {
        for (int i = 0; i + 1 < kTestF; ++i) {
            const Mat3 F = testF(i), ref = umrCauchy(F, c1, c2, k);
            CAPTURE(i);
            CHECK((lawCauchy(m, F) - ref).norm() < 1e-10 * ref.norm());
        }
    }
}

TEST_CASE("Gent: mu gamma / (1 - gamma^2/Jm) in simple shear, the neo-Hookean as Jm grows, finite past the lock", "[Gent]") {
    const double mu = 1000, Jm = 2, k = 20000;
    core::Node root("root");
    const BaseMaterial& m = addVariant(root, "GENT");
    CHECK(m.shearModulus() == mu);
    CHECK(m.bulkModulus() == k);
    SECTION("simple shear (Gent 1996): I1bar - 3 = gamma^2") {
        for (double g : {0.3, 1.0, 1.35}) {
            const Mat3 s = lawCauchy(m, simpleShear(g));
            const double tau = mu * g / (1 - g * g / Jm);
            CAPTURE(g);
            CHECK(s(0, 1) == Approx(tau).epsilon(1e-11));
            CHECK(s(0, 0) - s(1, 1) == Approx(tau * g).epsilon(1e-11));
            CHECK(std::abs(s(1, 1) - s(2, 2)) < 1e-11 * tau);
        }
    }
    SECTION("a general compressible deformation") {
        for (int i = 0; i + 1 < kTestF; ++i) {
            const Mat3 F = testF(i), ref = gentCauchy(F, mu, Jm, k);
            CAPTURE(i);
            CHECK((lawCauchy(m, F) - ref).norm() < 1e-10 * ref.norm());
        }
    }
    SECTION("Jm -> infinity: the deviatoric stress of the neo-Hookean mu/2 (I1bar - 3)") {
        const BaseMaterial& big = addMaterial(root, "Gent", {{"mu", "1000"}, {"Jm", "1e9"}, {"k", "20000"}}, "big");
        const BaseMaterial& nh = addMaterial(root, "NeoHookean", {{"mu", "1000"}, {"kappa", "20000"}}, "nh");
        for (int i = 0; i + 1 < kTestF; ++i) {
            const Mat3 a = dev(lawCauchy(big, testF(i))), b = dev(lawCauchy(nh, testF(i)));
            CAPTURE(i);
            CHECK((a - b).norm() < 1e-7 * b.norm());
        }
    }
    SECTION("past the lock: the second-order Taylor polynomial in x = (I1bar - 3)/Jm at x = 0.99") {
        const double a = 0.5 * mu * Jm, xL = 0.99;
        const auto f = [&](double x) { return -a * std::log(1 - x); };
        double prevTau = 0;
        for (double g : {1.30, 1.40, 1.45, 2.0, 3.0, 10.0}) {
            const double x = g * g / Jm;
            const double ref = x <= xL ? f(x) : f(xL) + a / (1 - xL) * (x - xL) + 0.5 * a / ((1 - xL) * (1 - xL)) * (x - xL) * (x - xL);
            const Mat3 s = lawCauchy(m, simpleShear(g));
            CAPTURE(g, x);
            CHECK(energyOfF(m, simpleShear(g)) == Approx(ref).epsilon(1e-10));
            CHECK(std::isfinite(s.norm()));
            CHECK(s(0, 1) > prevTau);  // still stiffening: the extension is convex
            prevTau = s(0, 1);
            const auto rep = conf::checkLawDerivatives(m, conf::invariantsOf(simpleShear(g)), 0.4);
            CHECK(rep.maxRelError < 1e-7);
        }
        // W and dW/dI1 continuous at the switch
        const double g0 = std::sqrt(xL * Jm);
        const Invariants lo = conf::invariantsOf(simpleShear(g0 * (1 - 1e-9))), hi = conf::invariantsOf(simpleShear(g0 * (1 + 1e-9)));
        const Response rl = conf::evaluateOne(m, lo, 0.4), rh = conf::evaluateOne(m, hi, 0.4);
        CHECK(rh.W == Approx(rl.W).epsilon(1e-6));
        CHECK(rh.dI1 == Approx(rl.dI1).epsilon(1e-6));
    }
}

// ---- through the force fields ---------------------------------------------------------------------

TEST_CASE("the new laws pass the conformance harness through HEMLForceField", "[HEMLForceField][conformance]") {
    const std::string variant = GENERATE(from_range(std::begin(kVariants), std::end(kVariants)));
    const bool generic = GENERATE(false, true);
    const MeshData mesh = boxMesh(3, 2, 2, false, 0.01, 0.15);
    Rig<heml::HEMLForceField> rig(mesh, variant, generic);
    CHECK(rig.ff->usesFastPath() == !generic);  // the inlined loop of each new law
    const auto rep = conf::checkForceField(*rig.ff, *rig.state);
    INFO(variant << (generic ? " (generic path)" : "") << ": gradient " << rep.gradientError << " rest " << rep.restForce
                 << " rotation " << rep.rotationError << " energy rotation " << rep.energyRotationError);
    CHECK(rep.forceScale > 0);
    CHECK(rep.gradientError < 1e-7);
    CHECK(rep.rotationError < 1e-10);
    CHECK(rep.energyRotationError < 1e-10);
    CHECK(rep.restForce < 1e-10);
    if (variant == "HGO2") {
        // the fibres are loaded in the harness's deformed state
        Rig<heml::HEMLForceField> matrix(mesh, "HGO0", generic);
        CHECK(rep.energy > 1.05 * conf::checkForceField(*matrix.ff, *matrix.state).energy);
    }
}

TEST_CASE("the new laws pass the conformance harness through TLEDForceField", "[TLEDForceField][conformance]") {
    const std::string variant = GENERATE(from_range(std::begin(kVariants), std::end(kVariants)));
    const bool hexes = GENERATE(false, true);
    const bool generic = GENERATE(false, true);
    const MeshData mesh = boxMesh(2, 2, 2, hexes, 0.05, 0.1);
    Rig<tled::TLEDForceField> rig(mesh, variant, generic);
    const auto rep = conf::checkForceField(*rig.ff, *rig.state);
    INFO(variant << (hexes ? " hexahedra" : " tetrahedra") << (generic ? " (generic path)" : "") << ": gradient "
                 << rep.gradientError << " rest " << rep.restForce << " rotation " << rep.rotationError);
    CHECK(rep.forceScale > 0);
    CHECK(rep.gradientError < 1e-6);
    CHECK(rep.rotationError < 1e-10);
    CHECK(rep.energyRotationError < 1e-10);
    CHECK(rep.restForce < 1e-12);
    if (variant == "HGO2") {
        Rig<tled::TLEDForceField> matrix(mesh, "HGO0", generic);
        CHECK(rep.energy > 1.05 * conf::checkForceField(*matrix.ff, *matrix.state).energy);
    }
}

TEST_CASE("TLEDForceField and HEMLForceField give the closed-form stresses of the new laws", "[TLEDForceField][HEMLForceField]") {
    struct Case {
        std::string variant;
        Mat3 F;
        Mat3 sigma;
    };
    const Vec3 l(1.25, 0.92, 0.95);  // stretches a0 = x, compresses b0 = y
    const Case cases[] = {
        {"HGOx", l.asDiagonal(), hgoPrincipalCauchy(l, 1000, 3000, 4, 0.1, 20000, true)},
        {"AB", simpleShear(0.6), abCauchy(simpleShear(0.6), 1000, 2, 20000)},
        {"AB", testF(0), abCauchy(testF(0), 1000, 2, 20000)},
        {"UMR", simpleShear(0.7), umrCauchy(simpleShear(0.7), 400, 150, 20000)},
        {"UMR", testF(1), umrCauchy(testF(1), 400, 150, 20000)},
        {"GENT", simpleShear(0.9), gentCauchy(simpleShear(0.9), 1000, 2, 20000)},
        {"GENT", testF(0), gentCauchy(testF(0), 1000, 2, 20000)},
    };
    for (const Case& c : cases) {
        CAPTURE(c.variant, c.F);
        for (bool hexes : {false, true}) {
            Rig<tled::TLEDForceField> rig(boxMesh(1, 1, 1, hexes, 0.1), c.variant);
            rig.deform(c.F);
            for (size_t e = 0; e < rig.ff->elementCount(); ++e) {
                const Mat3 s = fromVoigt(rig.cell("cauchyStress", e));
                CAPTURE(hexes, e, s);
                CHECK((s - c.sigma).norm() < 1e-10 * c.sigma.norm());
            }
        }
        // HEML reports the von Mises stress of the same Cauchy stress
        Rig<heml::HEMLForceField> rig(boxMesh(1, 1, 1, false, 0.1), c.variant);
        rig.deform(c.F);
        for (size_t e = 0; e < rig.ff->elementCount(); ++e) CHECK(rig.cell("vonMises", e)[0] == Approx(vonMises(c.sigma)).epsilon(1e-10));
    }
}

TEST_CASE("the stable time step of Arruda-Boyce uses its small-strain shear modulus", "[ArrudaBoyce][TLEDForceField][HEMLForceField]") {
    // a neo-Hookean with mu = the Arruda-Boyce mu0 and the same bulk modulus has the same wave speed
    // mu0 = mu sum_i 2 i C_i 3^(i-1) / lm^(2i-2) with mu = 1000, lm = 2 (variant AB)
    const double C[5] = {1.0 / 2, 1.0 / 20, 11.0 / 1050, 19.0 / 7000, 519.0 / 673750};
    double m0 = 0;
    for (int i = 1; i <= 5; ++i) m0 += 1000 * 2 * i * C[i - 1] * std::pow(3.0, i - 1) / std::pow(2.0, 2 * i - 2);
    std::ostringstream mu0;
    mu0.precision(17);
    mu0 << m0;
    const ParamList nh = {{"mu", mu0.str()}, {"kappa", "20000"}};
    const MeshData mesh = boxMesh(2, 1, 1, false, 0.02, 0.1);
    Rig<tled::TLEDForceField> tAB(mesh, "AB"), tNH(mesh, "NeoHookean", nh);
    const double dt = tAB.ff->stableTimeStep(*tAB.state);
    CHECK(std::isfinite(dt));
    CHECK(dt == Approx(tNH.ff->stableTimeStep(*tNH.state)).epsilon(1e-12));
    Rig<heml::HEMLForceField> hAB(mesh, "AB"), hNH(mesh, "NeoHookean", nh);
    const double dth = hAB.ff->stableTimeStep(*hAB.state);
    CHECK(std::isfinite(dth));
    CHECK(dth == Approx(hNH.ff->stableTimeStep(*hNH.state)).epsilon(1e-12));
}

TEST_CASE("HGO waves: the rest wave speed includes the small-strain fibre stiffness 2 k1 (1 - 3 kappa)^2 per family", "[HolzapfelGasserOgden]") {
    core::Node root("root");
    const BaseMaterial& two = addVariant(root, "HGO2", "two");
    const BaseMaterial& one = addVariant(root, "HGO1", "one");
    const double b = 1 - 3 * 0.1;
    CHECK(two.waveSpeed(1000) == Approx(std::sqrt((20000 + 4.0 / 3 * 1000 + 2 * 2 * 3000 * b * b) / 1000)).epsilon(1e-14));
    CHECK(one.waveSpeed(1000) == Approx(std::sqrt((15000 + 4.0 / 3 * 800 + 2 * 5000) / 1000)).epsilon(1e-14));
    // the fibre energy at small strain is 2 k1 (1 - 3 kappa)^2 (a0.dev(eps) a0)^2: check on a small stretch along a0
    const Vec3 a = *two.fibreDirection(0);
    const double e = 1e-5;
    const Mat3 F = Mat3::Identity() + e * a * a.transpose();
    core::Node r2("r2");
    const BaseMaterial& matrix = addVariant(r2, "HGO0");
    const double Wf = energyOfF(two, F) - energyOfF(matrix, F);
    const double devAA = e - e / 3;  // a0.dev(eps) a0 for eps = e a0 a0^T
    CHECK(Wf == Approx(2 * 3000 * b * b * devAA * devAA).epsilon(1e-4));
    CHECK(one.fibreDirection(1) != nullptr);  // the unused slot is filled (force fields read I6)
    CHECK(two.shearModulus() == 1000);
    CHECK(two.bulkModulus() == 20000);
}

// ---- parameters, --list and --describe --------------------------------------------------------------

TEST_CASE("invalid parameters of the new laws are located errors", "[HolzapfelGasserOgden][ArrudaBoyce][UncoupledMooneyRivlin]") {
    core::Node root("root");
    auto expectError = [&](const std::string& type, const ParamList& params, const std::string& what) {
        auto& m = addLaw(root, type, "m" + std::to_string(root.components().size()));
        CAPTURE(type, what);
        try {
            readParams(m, params, 7);
            m.init();
            FAIL("no error");
        } catch (const core::Error& e) {
            CHECK_THAT(e.what(), Catch::Contains("scene.xml:7") && Catch::Contains(what));
        }
    };
    const ParamList hgo = {{"mu", "1000"}, {"k1", "100"}, {"bulkModulus", "5000"}};
    auto with = [](ParamList p, const std::string& k, const std::string& v) {
        p.emplace_back(k, v);
        return p;
    };
    expectError("HolzapfelGasserOgden", with(hgo, "k2", "-1"), "k2 = -1");
    expectError("HolzapfelGasserOgden", with(hgo, "dispersion", "0.34"), "dispersion = 0.34");
    expectError("HolzapfelGasserOgden", with(hgo, "dispersion", "-0.01"), "dispersion = -0.01");
    expectError("HolzapfelGasserOgden", with(hgo, "k1", "-5"), "k1 = -5");
    expectError("HolzapfelGasserOgden", with(with(with(hgo, "k2", "1"), "direction", "0 0 1"), "direction2", "0 0 -2"), "parallel");
    expectError("HolzapfelGasserOgden", with(with(hgo, "k2", "1"), "direction", "0 0 0"), "non-zero");
    expectError("ArrudaBoyce", {{"mu", "1000"}, {"kappa", "5000"}, {"lambdaM", "1"}}, "lambdaM = 1");
    expectError("ArrudaBoyce", {{"mu", "1000"}, {"kappa", "5000"}, {"lambdaM", "0.7"}}, "lambdaM = 0.7");
    expectError("UncoupledMooneyRivlin", {{"c1", "100"}, {"c2", "-100"}, {"k", "5000"}}, "c1 + c2");
    expectError("UncoupledMooneyRivlin", {{"c1", "100"}, {"k", "0"}}, "k = 0");
    // the bulk modulus of HGO is not called kappa (kappa is HGO's dispersion): no such parameter
    CHECK(addLaw(root, "HolzapfelGasserOgden", "noKappa").findParam("kappa") == nullptr);
}

TEST_CASE("the registry lists the new laws with their energies in full", "[HolzapfelGasserOgden][ArrudaBoyce][UncoupledMooneyRivlin]") {
    core::PluginManager::instance().load("fascia_materials");
    const auto& reg = core::Registry::instance();
    const std::map<std::string, std::vector<std::string>> expected = {
        {"HolzapfelGasserOgden", {"mu/2 (I1bar - 3) + k1/(2 k2) sum_{i=4,6} [exp(k2 <E_i>^2) - 1] + k/2 (ln J)^2",
                                  "E_i = kappa (I1bar - 3) + (1 - 3 kappa)(I_ibar - 1)", "max(E, 0)"}},
        {"ArrudaBoyce", {"mu sum_{i=1}^{5} C_i/lambdaM^(2i-2) (I1bar^i - 3^i) + kappa/2 (J - 1)^2", "1/2, 1/20, 11/1050, 19/7000, 519/673750"}},
        {"UncoupledMooneyRivlin", {"C1 (I1bar - 3) + C2 (I2bar - 3) + k/2 (ln J)^2", "C1 = c1, C2 = c2"}},
        {"Gent", {"-mu Jm/2 ln(1 - (I1bar - 3)/Jm) + k/2 (ln J)^2", "beyond I1bar - 3 = 0.99 Jm"}},
    };
    const std::map<std::string, std::vector<std::string>> params = {
        {"HolzapfelGasserOgden", {"mu", "k1", "k2", "dispersion", "bulkModulus", "direction", "direction2"}},
        {"ArrudaBoyce", {"mu", "lambdaM", "kappa"}},
        {"UncoupledMooneyRivlin", {"c1", "c2", "k"}},
        {"Gent", {"mu", "Jm", "k"}},
    };
    for (const auto& [name, parts] : expected) {
        CAPTURE(name);
        const core::ComponentEntry* e = reg.find(name);
        REQUIRE(e);
        CHECK(e->plugin == "fascia.materials");
        for (const auto& p : parts) CHECK_THAT(e->description, Catch::Contains(p));
        auto c = reg.create(name);
        std::vector<std::string> got;
        for (core::BaseParam* p : c->params()) {
            if (p->name() == "name") continue;  // every component's
            got.push_back(p->name());
            CAPTURE(p->name());
            CHECK_FALSE(p->spec().helpText.empty());
        }
        CHECK(got == params.at(name));
    }
}
