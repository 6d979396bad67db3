// The device step's kernel bodies run on the CPU (CudaStep emulate="true", or a runner from
// makeEmulatedRunner) over the layout and host-side setup the GPU uses, against TLEDForceField and
// SemiImplicitEuler: this catches layout, indexing and setup errors in CI, where there is no GPU.
#include "CudaTestSupport.h"
#include "GroupCases.h"

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
    const double err = forceError(cuda::makeEmulatedRunner, p, useFloat ? cuda::Precision::Float : cuda::Precision::Double);
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
    const Pair r = runBoth(law, "", "<SemiImplicitEuler damping=\"5\"/>", Mesh::Tets,
                           "<CudaStep emulate=\"true\" blockSize=\"64\" precision=\"" + precision + "\"/>", 400);
    CAPTURE(sci(r.err));
    CHECK(r.err <= (deviceTolerance(precision)));
    CHECK(r.moved > 1e-5);  // (a trajectory that stayed at rest would compare well too)
}

TEST_CASE("CudaStep emulated follows the CPU trajectory of hexahedra with hourglass control over 1000 steps", "[CudaStep]") {
    const Mesh mesh = GENERATE(Mesh::Hexes, Mesh::Mixed);
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(meshName(mesh), law.name, precision);
    const Pair r = runBoth(law, "", "<SemiImplicitEuler damping=\"5\"/>", mesh, emulated(precision), 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= (deviceTolerance(precision)));
    CHECK(r.moved > 1e-4);
}

TEST_CASE("CudaStep emulated follows CentralDifference over 1000 steps", "[CudaStep]") {
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Mixed);
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    const bool damped = GENERATE(false, true);
    CAPTURE(meshName(mesh), law.name, precision, damped);
    const Pair r = runBoth(law, "", damped ? "<CentralDifference damping=\"5\"/>" : "<CentralDifference/>", mesh, emulated(precision), 1000);
    CAPTURE(sci(r.err));
    // (in double the CPU's own rounding dominates: its recurrence in x sums the rounding of x, about
    // 3e-18 m a step, twice, to about 1e-11 of this motion; damped, it also forms X c1 (2 - c2), which
    // is 1 - 2e-16 rather than 1 at dt = 2e-5: a spurious 1e-16 X a step, about 1e-9 of this motion.
    // The device's u = x - X has neither.)
    CHECK(r.err <= (precision == "float" ? 1e-4 : damped ? 5e-9 : 1e-10));
    CHECK(r.moved > 1e-4);
}

TEST_CASE("CudaStep emulated follows PrescribedDisplacement with either integrator over 1000 steps", "[CudaStep]") {
    const std::string integrator = GENERATE(as<std::string>{}, "<SemiImplicitEuler damping=\"5\"/>", "<CentralDifference damping=\"5\"/>",
                                            "<SemiImplicitEuler halfStepStart=\"false\"/>");
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Mixed);
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(integrator, meshName(mesh), precision);
    const Pair r = runBoth(deviceLaw("NeoHookean"), kLift, integrator, mesh, emulated(precision), 1000);
    CAPTURE(sci(r.err));
    const bool central = integrator.find("CentralDifference") != std::string::npos;  // (damped: see above)
    CHECK(r.err <= (precision == "float" ? 1e-4 : central ? 5e-9 : 1e-11));
    // the lifted axes where the lift puts them at t = 0.02 (past the ramp: d), the clamped x at rest
    for (size_t n : {size_t(12), size_t(30), size_t(31)}) {
        CAPTURE(n);
        CHECK(std::abs(r.device[n][1] - r.rest[n][1] - 0.001) <= 1e-9);
        CHECK(std::abs(r.device[n][2] - r.rest[n][2] - 0.002) <= 1e-9);
    }
    CHECK(r.device[12][0] == r.rest[12][0]);
    CHECK(r.device[30][0] != r.rest[30][0]);  // x free
}

TEST_CASE("CentralRule restarts CentralDifference on the first step and after a change of dt", "[CudaStep]") {
    cuda::CentralRule rule;
    cuda::NodeParams<double> p{};
    const double dts[] = {1e-5, 1e-5, 1e-5, 2e-5, 2e-5};
    const bool starts[] = {true, false, false, true, false}, twos[] = {false, true, true, false, true};
    for (int k = 0; k < 5; ++k) {
        CAPTURE(k);
        rule.next(dts[k], p);
        CHECK(p.start == starts[k]);
        CHECK(p.twoSteps == twos[k]);
    }
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

TEST_CASE("A component the device step cannot run is a located error naming it", "[CudaStep]") {
    const Law law = deviceLaw("NeoHookean");
    const std::string emu = "<CudaStep emulate=\"true\"/>";
    struct Case {
        std::string xml, expect;
    };
    const std::vector<Case> cases = {
        {scene(law, emu, "", "<ExplicitEuler/>"), "ExplicitEuler"},
        {scene(law, emu, "<HEMLForceField name=\"heml\"/>"), "HEMLForceField"},
        {scene(law, emu, "<ViscoelasticProny name=\"visco\" alpha=\"0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05 0.05\" tau=\"1 1 1 1 1 1 1 1 1\"/>"),
         "a Prony series of 9 terms"},
    };
    for (const Case& c : cases) {
        const std::string err = initError(c.xml);
        CAPTURE(c.xml, err);
        CHECK(err.find(c.expect) != std::string::npos);
        CHECK(err.find("<string>:") == 0);
        CHECK(err.find("not on the GPU step") != std::string::npos);
    }
}

TEST_CASE("CudaStep emulated follows TLEDForceField with a Prony series over 1000 steps", "[CudaStep][ViscoelasticProny]") {
    const std::string integrator = GENERATE(as<std::string>{}, "<SemiImplicitEuler damping=\"5\"/>", "<CentralDifference/>",
                                            "<CentralDifference damping=\"5\"/>");
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Mixed);
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(integrator, meshName(mesh), precision);
    const Pair r = runBoth(deviceLaw("TransverselyIsotropic"), prony(), integrator, mesh, emulated(precision), 1000);
    CAPTURE(sci(r.err));
    // (CentralDifference in double: the CPU's rounding in x, see above)
    const bool damped = integrator == "<CentralDifference damping=\"5\"/>", central = integrator.find("Central") != std::string::npos;
    CHECK(r.err <= (precision == "float" ? 1e-4 : damped ? 5e-9 : central ? 1e-10 : 1e-11));
    CHECK(r.moved > 1e-4);
}

TEST_CASE("CudaStep emulated relaxes: the viscous trajectory leaves the elastic one by far more than its error", "[CudaStep][ViscoelasticProny]") {
    const Law law = deviceLaw("TransverselyIsotropic");
    const Pair visco = runBoth(law, prony(), "<SemiImplicitEuler damping=\"5\"/>", Mesh::Mixed, emulated("double"), 1000);
    const Pair elastic = runBoth(law, "", "<SemiImplicitEuler damping=\"5\"/>", Mesh::Mixed, emulated("double"), 1000);
    const double apart = displacementError(visco.device, elastic.device, visco.rest);
    CAPTURE(sci(apart), sci(visco.err));
    CHECK(apart >= 0.05);  // (alpha_inf = 0.3: the relaxed body sags further)
    CHECK(visco.err <= 1e-11);
}

TEST_CASE("CudaStep emulated relaxes either part, or both, of every law as TLEDForceField does, or refuses as it does",
          "[CudaStep][ViscoelasticProny]") {
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string apply = GENERATE(as<std::string>{}, "isochoric", "volumetric", "both");
    CAPTURE(law.name, apply);
    const std::string cpuError = initError(scene(law, "", prony(apply)));
    if (!cpuError.empty()) {
        // the CPU refuses this part of this law (it carries a stress at rest): the device step too, at the series' apply
        const std::string err = initError(scene(law, emulated("double"), prony(apply)));
        CAPTURE(cpuError, err);
        CHECK(err == cpuError);
        CHECK(err.find("<string>:") == 0);
        CHECK(err.find("ViscoelasticProny 'visco'") != std::string::npos);
        return;
    }
    // (500 steps: the laws without a volumetric term, their shear relaxed, let this body collapse under
    // its load later on, where the round-off of any two computations grows exponentially: 1e-13 at 600
    // steps, 1e-6 at 1000)
    for (const std::string precision : {"double", "float"}) {
        CAPTURE(precision);
        const Pair r = runBoth(law, prony(apply), "<SemiImplicitEuler damping=\"5\"/>", Mesh::Mixed, emulated(precision), 500);
        CAPTURE(sci(r.err));
        CHECK(r.err <= (precision == "float" ? 1e-4 : 1e-11));
        CHECK(r.moved > 1e-4);
    }
}

TEST_CASE("CudaStep emulated runs a series per part, of different lengths, as TLEDForceField does", "[CudaStep][ViscoelasticProny]") {
    // CompressibleNeoHookean: s ln J moved between the parts (materials/RelaxationSplit.h)
    const Law law = GENERATE(deviceLaw("CompressibleNeoHookean"), deviceLaw("HolzapfelGasserOgden"));
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(law.name, precision);
    const Pair r = runBoth(law, kTwoSeries, "<SemiImplicitEuler damping=\"5\"/>", Mesh::Mixed, emulated(precision), 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= (precision == "float" ? 1e-4 : 1e-11));
    CHECK(r.moved > 1e-4);
}

TEST_CASE("The device step's own setup refuses a series on a part that carries a stress at rest, at its apply", "[CudaStep][ViscoelasticProny]") {
    // (TLEDForceField refuses it first at init: here the series' part is changed after init, so that the
    // device step's check alone answers)
    for (const Law& law : deviceLaws())
        for (const std::string apply : {"isochoric", "volumetric", "both"}) {
            const std::string cpuError = initError(scene(law, "", prony(apply)));
            if (cpuError.empty()) continue;
            CAPTURE(law.name, apply, cpuError);
            std::string valid;
            for (const std::string a : {"isochoric", "volumetric", "both"})
                if (valid.empty() && initError(scene(law, "", prony(a))).empty()) valid = a;
            if (valid.empty()) continue;  // (no value is valid for this law)
            auto sim = core::Simulation::fromString(scene(law, "", prony(valid)));
            sim->init();
            auto* part = dynamic_cast<core::Param<std::string>*>(sim->find("visco")->findParam("apply"));
            REQUIRE(part);
            part->set(apply);
            std::string err;
            try {
                cuda::buildStepSetup(*sim->find("ff"), sim->groups().at(0));
            } catch (const core::Error& e) {
                CHECK(e.kind() == core::ErrorKind::Input);
                err = e.what();
            }
            CAPTURE(err);
            CHECK(err == cpuError);
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
    const std::string err = initError(*sim);
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

TEST_CASE("The emulated kernels give TLED's forces with materials per group and fibres per element", "[CudaStep][groupMaterials]") {
    groups::forcesMatch(cuda::makeEmulatedRunner);
}

TEST_CASE("CudaStep emulated follows TLEDForceField with materials per group and fibres per element over 1000 steps",
          "[CudaStep][groupMaterials]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    groups::trajectoriesFollow(emulated(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep emulated relaxes materials per group with fibres per element as TLEDForceField does",
          "[CudaStep][groupMaterials][ViscoelasticProny]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    groups::relaxedGroupsFollow(emulated(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep emulated reads the fibre arrays and the groups: their trajectories leave the uniform ones by far more than their error",
          "[CudaStep][groupMaterials]") {
    groups::arraysAndGroupsMatter(emulated("double"), 1e-11);
}

TEST_CASE("A group whose material is not a device law is a located error naming it", "[CudaStep][groupMaterials]") {
    // a user's law (not a Material<Law> of the built-in list) in group 2, added before init (fromString
    // initialises at once); TLEDForceField runs it on the CPU
    groups::GroupCase c = groups::groupCase("three groups");
    c.ff = " groupMaterials=\"1 @a 2 @user 3 @c 4 @a\"";
    auto sim = std::make_unique<core::Simulation>(core::buildScene(
        core::parseSceneString(scene(groups::groupParts(c, Mesh::Mixed), "<CudaStep emulate=\"true\"/>"), "<string>", ".")));
    auto* mat = dynamic_cast<fascia::materials::BaseMaterial*>(sim->find("b"));
    auto* ff = sim->find("ff");
    REQUIRE(mat);
    REQUIRE(ff);
    auto& user = ff->node()->add<fascia::materials::conformance::GenericMaterial>("user");
    user.inner = mat;
    const std::string err = initError(*sim);
    CAPTURE(err);
    // located at the groupMaterials that names it (the material, added from code, has no line)
    CHECK(err.find("<string>:9: error: TLEDForceField 'ff': groupMaterials: the material GenericMaterial 'user'") == 0);
    CHECK(err.find("not on the GPU step") != std::string::npos);
    CHECK(err.find(cuda::deviceLawNames()) != std::string::npos);
}
