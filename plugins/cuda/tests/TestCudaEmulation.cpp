// The device step's kernel bodies run on the CPU (CudaStep emulate="true", or a runner from
// makeEmulatedRunner) over the layout and host-side setup the GPU uses, against TLEDForceField and
// SemiImplicitEuler: this catches layout, indexing and setup errors in CI, where there is no GPU.
#include "CudaTestSupport.h"

#include "fascia/base/Error.h"
#include "fascia/materials/Conformance.h"
#include "fascia/scene/SceneLoader.h"

#include <set>

using namespace cudatest;

TEST_CASE("The emulated element and node kernels give TLED's forces on every node", "[CudaStep]") {
    const Law law = GENERATE(from_range(deviceLaws()));
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Hexes, Mesh::Mixed);
    const double scale = GENERATE(0.3, 1.0, 3.0);  // 3: some elements below J0
    const bool useFloat = GENERATE(false, true);
    CAPTURE(law.name, meshName(mesh), scale, useFloat);
    ForceProbe p = probeForces(law, scale, mesh);
    REQUIRE(p.setup.nTets == (mesh == Mesh::Hexes ? 0 : mesh == Mesh::Tets ? 72 : 48));
    REQUIRE(p.setup.nHexes == (mesh == Mesh::Tets ? 0 : mesh == Mesh::Hexes ? 12 : 4));
    for (double K : p.setup.hgK) REQUIRE(K > 0);  // the hourglass forces take part
    auto runner = cuda::makeEmulatedRunner(p.setup, useFloat ? cuda::Precision::Float : cuda::Precision::Double);
    runner->setState(p.u, p.v);
    runner->elementPass();
    std::vector<double> f;
    runner->internalForces(f);
    REQUIRE(f.size() == 3 * p.f.size());
    const double err = relativeError(f, p.f);
    CAPTURE(sci(err));
    CHECK(err <= (useFloat ? 1e-5 : 1e-12));
}

TEST_CASE("The slot lists give every element corner to its node once, by element then corner", "[CudaStep]") {
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Hexes, Mesh::Mixed);
    CAPTURE(meshName(mesh));
    ForceProbe p = probeForces(deviceLaw("NeoHookean"), 1.0, mesh);
    const cuda::StepSetup& s = p.setup;
    REQUIRE(s.slotStart.size() == size_t(s.nNodes) + 1);
    REQUIRE(s.slotStart.back() == 4 * s.nTets + 8 * s.nHexes);
    std::set<std::uint32_t> seen;
    for (int n = 0; n < s.nNodes; ++n)
        for (int k = s.slotStart[size_t(n)]; k < s.slotStart[size_t(n) + 1]; ++k) {
            const std::uint32_t slot = s.slots[size_t(k)];
            const size_t e = slot >> 3, a = slot & 7u;
            if (e < size_t(s.nTets)) {
                CHECK(a < 4);
                CHECK(s.tet[a * size_t(s.nTets) + e] == n);
            } else {
                CHECK(s.hex[a * size_t(s.nHexes) + e - size_t(s.nTets)] == n);
            }
            if (k > s.slotStart[size_t(n)]) CHECK(s.slots[size_t(k) - 1] < slot);
            seen.insert(slot);
        }
    CHECK(seen.size() == size_t(4 * s.nTets + 8 * s.nHexes));
}

TEST_CASE("CudaStep emulated follows the CPU trajectory over 400 steps", "[CudaStep]") {
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(law.name, precision);
    const int steps = 400;
    auto ref = core::Simulation::fromString(scene(law, ""));
    ref->init();
    for (int s = 0; s < steps; ++s) ref->step();
    const Positions x = trajectoryEnd(law, "<CudaStep emulate=\"true\" blockSize=\"64\" precision=\"" + precision + "\"/>", steps);
    const auto& mo = ref->state("mo");
    const double err = displacementError(x, mo.x(), mo.x0());
    CAPTURE(sci(err));
    CHECK(err <= (precision == "double" ? 1e-11 : 1e-4));
    // the body moved (a trajectory that stayed at rest would compare well too)
    double moved = 0;
    for (size_t i = 0; i < x.size(); ++i) moved = std::max(moved, (mo.x()[i] - mo.x0()[i]).norm());
    CHECK(moved > 1e-5);
}

TEST_CASE("CudaStep emulated follows the CPU trajectory of hexahedra with hourglass control over 1000 steps", "[CudaStep]") {
    const Mesh mesh = GENERATE(Mesh::Hexes, Mesh::Mixed);
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(meshName(mesh), law.name, precision);
    const int steps = 1000;
    auto ref = core::Simulation::fromString(scene(law, "", "", "<SemiImplicitEuler damping=\"5\"/>", mesh));
    ref->init();
    for (int s = 0; s < steps; ++s) ref->step();
    const Positions x = trajectoryEnd(law, "<CudaStep emulate=\"true\" precision=\"" + precision + "\"/>", steps, mesh);
    const auto& mo = ref->state("mo");
    const double err = displacementError(x, mo.x(), mo.x0());
    CAPTURE(sci(err));
    CHECK(err <= (precision == "double" ? 1e-11 : 1e-4));
    double moved = 0;
    for (size_t i = 0; i < x.size(); ++i) moved = std::max(moved, (mo.x()[i] - mo.x0()[i]).norm());
    CHECK(moved > 1e-4);
}

TEST_CASE("CudaStep emulated keeps the held axes at rest and starts the leapfrog like SemiImplicitEuler", "[CudaStep]") {
    const Law law = deviceLaw("CompressibleNeoHookean");
    for (const char* start : {"true", "false"}) {
        CAPTURE(start);
        const std::string integ = std::string("<SemiImplicitEuler halfStepStart=\"") + start + "\"/>";
        auto ref = core::Simulation::fromString(scene(law, "", "", integ));
        auto emu = core::Simulation::fromString(scene(law, "<CudaStep emulate=\"true\"/>", "", integ));
        ref->init();
        emu->init();
        for (int s = 0; s < 3; ++s) {
            ref->step();
            emu->step();
        }
        const auto& a = ref->state("mo");
        const auto& b = emu->state("mo");
        // (after 3 steps the displacements are about 1e-8 m: compare in ulps of the positions, about 0.03 m,
        // since the device step keeps u = x - X where SemiImplicitEuler updates x)
        double d = 0;
        for (size_t i = 0; i < a.size(); ++i) d = std::max(d, (b.x()[i] - a.x()[i]).norm());
        CHECK(d <= 1e-16);
        for (int n : {0, 4, 8}) CHECK((b.x()[size_t(n)] - b.x0()[size_t(n)]).norm() == 0.0);
        CHECK(b.x()[12][0] == b.x0()[12][0]);  // the roller holds x only
        CHECK(b.x()[12][1] != b.x0()[12][1]);
    }
}

namespace {

/// The Input error of initialising a scene (empty when it initialises).
std::string initError(const std::string& xml) {
    try {
        auto sim = core::Simulation::fromString(xml);
        sim->init();
    } catch (const core::Error& e) {
        CHECK(e.kind() == core::ErrorKind::Input);
        return e.what();
    }
    return {};
}

} // namespace

TEST_CASE("A component the device step cannot run is a located error naming it", "[CudaStep]") {
    const Law law = deviceLaw("NeoHookean");
    const std::string emu = "<CudaStep emulate=\"true\"/>";
    struct Case {
        std::string xml, expect;
    };
    const std::vector<Case> cases = {
        {scene(law, emu, "", "<CentralDifference/>"), "CentralDifference"},
        {scene(law, emu, "<PrescribedDisplacement indices=\"30\" displacement=\"0 0 0.001\"/>"), "PrescribedDisplacement"},
        {scene(law, emu, "<ConstantForce name=\"ramp\" indices=\"30\" force=\"0 0 1\" curve=\"linear 0 0 1 1\"/>"), "load curve"},
        {scene(law, emu, "<ViscoelasticProny name=\"visco\" alpha=\"0.5\" tau=\"0.1\"/>"), "ViscoelasticProny"},
    };
    for (const Case& c : cases) {
        const std::string err = initError(c.xml);
        CAPTURE(c.xml, err);
        CHECK(err.find(c.expect) != std::string::npos);
        CHECK(err.find("<string>:") == 0);
        CHECK(err.find("not on the GPU step") != std::string::npos);
    }
}

TEST_CASE("A material outside the device step's laws is an error naming it and the laws it runs", "[CudaStep]") {
    // a user's law (not a Material<Law> of the built-in list), wrapping the scene's NeoHookean
    // (built, then initialised once the material is in: fromString initialises at once)
    auto sim = std::make_unique<core::Simulation>(
        core::buildScene(core::parseSceneString(scene(deviceLaw("NeoHookean"), "<CudaStep emulate=\"true\"/>"), "<string>", ".")));
    auto* mat = dynamic_cast<fascia::materials::BaseMaterial*>(sim->find("mat"));
    auto* ff = sim->find("ff");
    REQUIRE(mat);
    REQUIRE(ff);
    auto& user = ff->node()->add<fascia::materials::conformance::GenericMaterial>("user");
    user.inner = mat;
    auto* link = dynamic_cast<core::Link<fascia::materials::BaseMaterial>*>(ff->findParam("material"));
    REQUIRE(link);
    link->set(&user);
    std::string err;
    try {
        sim->init();
    } catch (const core::Error& e) {
        CHECK(e.kind() == core::ErrorKind::Input);
        err = e.what();
    }
    CAPTURE(err);
    CHECK(err.find("GenericMaterial 'user'") != std::string::npos);  // (added from code: no line to locate)
    CHECK(err.find("not on the GPU step") != std::string::npos);
    CHECK(err.find(cuda::deviceLawNames()) != std::string::npos);
}

TEST_CASE("CudaStep outside the root node is a located error", "[CudaStep]") {
    std::string xml = scene(deviceLaw("NeoHookean"), "", "<CudaStep emulate=\"true\"/>");
    const std::string err = initError(xml);
    CAPTURE(err);
    CHECK(err.find("must be in the root node") != std::string::npos);
    CHECK(err.find("<string>:") == 0);
}

TEST_CASE("CudaStep without a usable device is a located input error, never a host fallback", "[CudaStep]") {
    std::string why;
    const int devices = cuda::cudaDevices(why);
    CAPTURE(why);
    const std::string err = initError(scene(deviceLaw("NeoHookean"), "<CudaStep/>"));
    CAPTURE(err);
    if (devices == 0) {
        CHECK(err.find("no usable CUDA device") != std::string::npos);
        CHECK(err.find("<string>:2:") == 0);
    } else {
        CHECK(err.empty());  // a machine with a GPU initialises the scene on it
    }
}
