// The hand-over from the element force fields to the device step (fascia/elements/DeviceForm.h):
// TLEDForceField's and HEMLForceField's device forms hold, in input order, bitwise the rest data
// the element layer's geometry gives (elements::tetRest, edgeRest, hexUniformStrain, the hourglass
// vectors and stiffnesses: what the device step computed itself before the forms existed), their
// materials as elements::assignMaterials assigns them, their fibres as elements::resolveFibres
// resolves them and their series; a force field, a constraint or an integrator that gives no such
// terms is refused by the device setup, located at it (docs/design.md, section 4.7).
#include "HEMLCases.h"

#include "fascia/elements/DeviceForm.h"
#include "fascia/elements/EdgeForm.h"
#include "fascia/elements/FibreField.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/GroupMaterials.h"
#include "fascia/elements/TetForceField.h"
#include "fascia/plugin/Registry.h"
#include "fascia/scene/Node.h"
#include "fascia/tled/TLEDForceField.h"

using namespace cudatest;
namespace elements = fascia::elements;
namespace materials = fascia::materials;
using fascia::Mat3;

namespace {

/// A user's force field on the element layer's per-element base (as examples/plugin's
/// CorotationalTetForceField): linear elasticity, no device form.
class UserTetForceField : public elements::TetForceField<UserTetForceField> {
public:
    double stress(const Mat3& F, Mat3& P) const {
        const Mat3 E = 0.5 * (F + F.transpose()) - Mat3::Identity();
        P = 2000.0 * E + 1000.0 * E.trace() * Mat3::Identity();
        return 1000.0 * E.squaredNorm() + 500.0 * E.trace() * E.trace();
    }
    double waveSpeed(double rho) const { return std::sqrt(4000.0 / rho); }
    core::Param<double> m_J0{this, core::ParamSpec("J0").help("test only: taken as the scenes give it"), 0.4};
};

/// A user's constraint: holds its nodes as FixedConstraint does, but gives no terms (core::AxisHold).
class UserConstraint : public core::BaseConstraint {
public:
    const fascia::IndexList& constrainedNodes() const override { return m_nodes; }
    fascia::IndexList m_nodes{0};
};

void registerUserComponents() {
    static const bool registered = [] {
        core::Registry::instance().add<UserTetForceField>("UserTetForceField", "test only: a user's force field with no device form");
        core::Registry::instance().add<UserConstraint>("UserConstraint", "test only: a user's constraint with no terms");
        return true;
    }();
    (void)registered;
}

/// The force field "ff" of an initialised scene and its device form.
struct FormProbe {
    std::unique_ptr<core::Simulation> sim;
    core::BaseForceField* ff = nullptr;
    elements::DeviceForm form;
};

FormProbe formOf(const std::string& xml) {
    FormProbe p;
    p.sim = core::Simulation::fromString(xml);
    p.sim->init();
    p.ff = dynamic_cast<core::BaseForceField*>(p.sim->find("ff"));
    REQUIRE(p.ff);
    const auto* source = dynamic_cast<const elements::DeviceFormSource*>(p.ff);
    REQUIRE(source);
    source->deviceForm(p.form);
    REQUIRE(p.form.tetrahedra == p.ff->tetrahedra());
    return p;
}

/// The force field's mesh source (null for elements given as lists), as its init finds it.
const fascia::MeshData* meshOf(const core::BaseForceField& ff) {
    for (const char* name : {"tetrahedra", "hexahedra"})
        if (const auto* p = ff.findParam(name); p && p->isSet()) return nullptr;
    const auto* source = ff.node()->findInContext<core::BaseTopology>();
    return source ? &source->meshData() : nullptr;
}

/// The material of each cell as elements::assignMaterials assigns them from the force field's
/// parameters (read by name: the test's reference), and the form's fibres against resolveFibres.
void checkMaterialsAndFibres(const core::BaseForceField& ff, const elements::DeviceForm& form, size_t nT, size_t nH, bool edges) {
    const auto* groups = dynamic_cast<const core::Param<elements::GroupMaterialList>*>(ff.findParam("groupMaterials"));
    const auto* link = dynamic_cast<const core::Link<materials::BaseMaterial>*>(ff.findParam("material"));
    REQUIRE(groups);
    REQUIRE(link);
    const fascia::MeshData* mesh = meshOf(ff);
    const elements::MaterialAssignment a = elements::assignMaterials(ff, *groups, elements::defaultMaterial(ff, *link, *groups), mesh, nT, nH);
    std::vector<const materials::BaseMaterial*> cells(a.tetrahedra.begin(), a.tetrahedra.end());
    cells.insert(cells.end(), a.hexahedra.begin(), a.hexahedra.end());
    CHECK(form.cellMaterial == cells);
    CHECK(form.groupMaterials == (groups->isSet() ? groups : nullptr));
    CHECK(form.material == elements::defaultMaterial(ff, *link, *groups));
    if (edges) return;
    bool perElement = false;
    for (int w = 0; w < 2; ++w) {
        const auto* array = dynamic_cast<const core::Param<std::string>*>(ff.findParam(w == 0 ? "fibreArray" : "fibreArray2"));
        REQUIRE(array);
        perElement |= elements::resolveFibres(ff, w, *array, mesh, cells, nT).perElement;
    }
    CHECK(form.fibresPerElement == perElement);
    for (int w = 0; w < 2; ++w) {
        const auto* array = dynamic_cast<const core::Param<std::string>*>(ff.findParam(w == 0 ? "fibreArray" : "fibreArray2"));
        const elements::FibreField f = elements::resolveFibres(ff, w, *array, mesh, cells, nT);
        CAPTURE(w);
        if (!perElement || !f.used) {
            CHECK(form.fibre[w].empty());
            continue;
        }
        REQUIRE(form.fibre[w].size() == 3 * (nT + nH));
        for (size_t c = 0; c < nT + nH; ++c) {
            const Vec3 d = f.dir[c] == Vec3::Zero() ? Vec3(w == 0 ? 1 : 0, w == 0 ? 0 : 1, 0) : f.dir[c];
            for (int i = 0; i < 3; ++i) CHECK(form.fibre[w][3 * c + size_t(i)] == d[i]);
        }
    }
}

/// TLED's rest data against the element layer's geometry (bitwise) and TLEDForceField::restVolume.
void checkTLEDRest(const FormProbe& p) {
    const elements::DeviceForm& form = p.form;
    REQUIRE(form.kind == elements::DeviceForm::Kind::TLED);
    REQUIRE(form.hexahedra == p.ff->hexahedra());
    const auto* tled = dynamic_cast<const fascia::tled::TLEDForceField*>(p.ff);
    REQUIRE(tled);
    const Positions& X = p.sim->state("mo").x0();
    const fascia::Tetrahedra& tets = *form.tetrahedra;
    const fascia::Hexahedra& hexes = *form.hexahedra;
    const size_t nT = tets.size(), nH = hexes.size();
    REQUIRE(form.tetDN.size() == 9 * nT);
    REQUIRE(form.tetVolume.size() == nT);
    const elements::TetRest rest = elements::tetRest(*p.ff, X, tets);
    int differ = 0;
    for (size_t e = 0; e < nT; ++e) {
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < 3; ++i) differ += form.tetDN[9 * e + size_t(3 * a + i)] != rest.DmInv[e](a, i);
        differ += form.tetVolume[e] != rest.volume[e];
        differ += form.tetVolume[e] != tled->restVolume(e);
    }
    REQUIRE(form.hexDN.size() == 24 * nH);
    REQUIRE(form.hexC.size() == 12 * nH);
    REQUIRE(form.hexVolume.size() == nH);
    REQUIRE(form.hexK.size() == nH);
    for (size_t e = 0; e < nH; ++e) {
        Vec3 P[8];
        for (size_t a = 0; a < 8; ++a) P[a] = X[size_t(hexes[e][a])];
        double V, dN[24], sumDN2, c[12];
        elements::hexUniformStrain(P, V, dN, sumDN2);
        elements::hexHourglassVectors(P, c);
        for (size_t r = 0; r < 24; ++r) differ += form.hexDN[24 * e + r] != dN[r];
        for (size_t r = 0; r < 12; ++r) differ += form.hexC[12 * e + r] != c[r];
        differ += form.hexVolume[e] != std::abs(V);
        differ += form.hexVolume[e] != tled->restVolume(nT + e);
        differ += form.hexK[e] != elements::hexHourglassStiffness(form.hourglass, *form.cellMaterial[nT + e], std::abs(V), sumDN2);
    }
    CHECK(differ == 0);
    CHECK(form.J0 == 0.3);
    CHECK(form.hourglass == 0.075);
    checkMaterialsAndFibres(*p.ff, form, nT, nH, false);
}

/// HEML's rest data against elements::edgeRest (bitwise): V, 1 / det V, G and the volumes, the
/// fibres' V^-1 a0 where the element's material reads them, the springs' shares and rest lengths.
void checkHEMLRest(const FormProbe& p, bool springs) {
    const elements::DeviceForm& form = p.form;
    REQUIRE(form.kind == (springs ? elements::DeviceForm::Kind::Springs : elements::DeviceForm::Kind::Edges));
    const Positions& X = p.sim->state("mo").x0();
    const fascia::Tetrahedra& tets = *form.tetrahedra;
    const size_t n = tets.size();
    REQUIRE(form.tetVolume.size() == n);
    REQUIRE(form.edgeV.size() == 9 * n);
    REQUIRE(form.edgeInvDetV.size() == n);
    REQUIRE(form.edgeG.size() == (springs ? 0 : 6 * n));
    REQUIRE(form.springK.size() == (springs ? 6 * n : 0));
    REQUIRE(form.springLength.size() == (springs ? 6 * n : 0));
    std::vector<Vec3> dir[2];
    if (!springs) {
        checkMaterialsAndFibres(*p.ff, form, n, 0, true);
        for (int w = 0; w < 2; ++w) {
            const auto* array = dynamic_cast<const core::Param<std::string>*>(p.ff->findParam(w == 0 ? "fibreArray" : "fibreArray2"));
            REQUIRE(array);
            dir[w] = elements::resolveFibres(*p.ff, w, *array, meshOf(*p.ff), form.cellMaterial, n).dir;
            CHECK(form.edgeW[w].size() == (dir[w].empty() ? 0 : 3 * n));
        }
    }
    const elements::EdgeShares shares(springs ? tets : fascia::Tetrahedra{});
    int differ = 0;
    for (size_t e = 0; e < n; ++e) {
        const auto& t = tets[e];
        const elements::EdgeRest r = elements::edgeRest(X[size_t(t[0])], X[size_t(t[1])], X[size_t(t[2])], X[size_t(t[3])]);
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < 3; ++i) differ += form.edgeV[9 * e + size_t(3 * a + i)] != r.V(i, a);
        differ += form.edgeInvDetV[e] != 1.0 / r.det;
        differ += form.tetVolume[e] != std::abs(r.det) / 6.0;
        for (size_t q = 0; q < form.edgeG.size() / n; ++q) differ += form.edgeG[6 * e + q] != r.G[q];
        for (int w = 0; w < 2; ++w) {
            if (form.edgeW[w].empty()) continue;
            const Vec3 v = dir[w][e].isZero() ? Vec3::Zero() : Vec3(r.Vi * dir[w][e]);
            for (int i = 0; i < 3; ++i) differ += form.edgeW[w][3 * e + size_t(i)] != v[i];
        }
        for (size_t q = 0; q < form.springK.size() / n; ++q) {
            const int a = t[size_t(elements::edgeA(int(q)))], b = t[size_t(elements::edgeB(int(q)))];
            differ += form.springK[6 * e + q] != 20.0 / shares.count(a, b);
            differ += form.springLength[6 * e + q] != (X[size_t(b)] - X[size_t(a)]).norm();
        }
    }
    CHECK(differ == 0);
    CHECK(form.J0 == 0.3);
}

/// The error of building the device step's setup of the scene's first group.
std::string setupError(const std::string& xml) {
    auto sim = core::Simulation::fromString(xml);
    sim->init();
    try {
        cuda::buildStepSetup(*sim->find("ff"), sim->groups().at(0));
    } catch (const core::Error& e) {
        CHECK(e.kind() == core::ErrorKind::Input);
        return e.what();
    }
    return {};
}

} // namespace

TEST_CASE("TLEDForceField's device form is its precompute's rest data, bitwise the element layer's, in input order", "[CudaStep][DeviceForm]") {
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Hexes, Mesh::Mixed);
    CAPTURE(meshName(mesh));
    SECTION("one material") {
        const FormProbe p = formOf(scene(deviceLaw("HolzapfelGasserOgden"), "", "", "<SemiImplicitEuler damping=\"5\"/>", mesh));
        checkTLEDRest(p);
        CHECK(p.form.series.empty());
    }
    SECTION("materials per group and fibre arrays") {
        for (const groups::GroupCase& c : groups::groupCases()) {
            CAPTURE(c.name);
            checkTLEDRest(formOf(scene(groups::groupParts(c, mesh), "")));
        }
    }
    SECTION("its Prony series, in its order") {
        const FormProbe p = formOf(scene(deviceLaw("NeoHookean"), "", kTwoSeries, "<SemiImplicitEuler damping=\"5\"/>", mesh));
        const std::vector<const core::Component*> series = {p.sim->find("shear"), p.sim->find("bulk")};
        CHECK(p.form.series == series);
    }
}

TEST_CASE("HEMLForceField's device form is its precompute's rest data, bitwise the element layer's, in input order", "[CudaStep][DeviceForm][HEML]") {
    SECTION("every law and the springs") {
        for (const std::string& name : heml::caseNames()) {
            CAPTURE(name);
            checkHEMLRest(formOf(scene(heml::caseParts(name), "")), name == "springs");
        }
    }
    SECTION("materials per group and fibre arrays") {
        for (const groups::GroupCase& c : groups::groupCases()) {
            CAPTURE(c.name);
            BodyParts body = groups::groupParts(c, Mesh::Tets);
            body.forceField = "HEMLForceField";
            checkHEMLRest(formOf(scene(body, "")), false);
        }
    }
    SECTION("its Prony series") {
        const FormProbe p = formOf(scene(heml::parts(deviceLaw("NeoHookean")), "", prony()));
        CHECK(p.form.series == std::vector<const core::Component*>{p.sim->find("visco")});
    }
}

TEST_CASE("A force field, constraint or integrator that gives the device step no terms is refused, located at it", "[CudaStep][DeviceForm]") {
    registerUserComponents();
    const Law law = deviceLaw("NeoHookean");
    const std::string grid = "<GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"tetrahedra6\"/>";
    const BodyParts user{grid, law.element, "", "UserTetForceField"};
    REQUIRE(initError(scene(user, "")).empty());  // (it runs on the CPU)
    struct Case {
        std::string xml, at, expect;
    };
    std::string none = scene(law, emulated("double"));
    const std::string ffLine = "    <TLEDForceField name=\"ff\" J0=\"0.3\"/>\n";
    REQUIRE(none.find(ffLine) != std::string::npos);
    none.erase(none.find(ffLine), ffLine.size());
    const std::vector<Case> cases = {
        // a user's force field on the element layer: no device form (elements::DeviceFormSource)
        {scene(user, emulated("double")), "<string>:9: error: UserTetForceField 'ff'", "elements::DeviceFormSource"},
        {scene(law, emulated("double"), "<UserTetForceField name=\"user\" J0=\"0.3\"/>"), "<string>:13: error: UserTetForceField 'user'",
         "elements::DeviceFormSource"},
        {scene(law, emulated("double"), "<UserConstraint name=\"hold\"/>"), "<string>:13: error: UserConstraint 'hold'", "core::AxisHold"},
        {scene(law, emulated("double"), "", "<ExplicitEuler/>"), "<string>:7: error: ExplicitEuler", "core::ExplicitScheme"},
        // no element force field at all: at CudaStep
        {none, "<string>:2: error: CudaStep", "has no element force field with a device form"},
    };
    for (const Case& c : cases) {
        const std::string err = initError(c.xml);
        CAPTURE(c.xml, err);
        CHECK(err.find(c.at) == 0);
        CHECK(err.find(c.expect) != std::string::npos);
        if (c.at.find("CudaStep") == std::string::npos) CHECK(err.find("not on the GPU step") != std::string::npos);
    }
}

TEST_CASE("A force field with its element data in float gives no device form: a located error at its precision", "[CudaStep][DeviceForm]") {
    const BodyParts tled{"<GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"hexahedra\"/>",
                         deviceLaw("NeoHookean").element, " precision=\"mixed\""};
    const BodyParts heml = heml::parts(deviceLaw("NeoHookean"), " precision=\"mixed\"");
    for (const BodyParts& body : {tled, heml}) {
        CAPTURE(body.forceField);
        REQUIRE(initError(scene(body, "")).empty());
        const std::string err = initError(scene(body, emulated("float")));
        CAPTURE(err);
        CHECK(err.find("<string>:9: error: " + body.forceField + " 'ff': ") == 0);
        CHECK(err.find("precision=\"mixed\"") != std::string::npos);
        CHECK(setupError(scene(body, "")) == err);  // (from the setup itself, as CudaStep's adopt calls it)
    }
}
