#pragma once
// The cases of HEMLForceField on the device step (StepSetup::Form::Edges: HEML's edge form,
// fascia/elements/EdgeForm.h, on the same slots and node kernel as TLED): every law, its
// mass-spring mode, a Prony series on either part or both, materials per group and fibre arrays,
// against HEMLForceField on the CPU. Run through the emulation (TestCudaHEML.cpp) and through real
// launches (TestCudaDevice.cpp) with the same checks.
#include "CudaTestSupport.h"
#include "GroupCases.h"

#include <functional>

namespace cudatest::heml {

/// The cantilever's tetrahedra (the grid's 6 per cell).
inline const std::string kGrid =
    "<GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"tetrahedra6\"/>";

/// HEML's cantilever with the law, `ff` its force field's further attributes.
inline BodyParts parts(const Law& law, const std::string& ff = "") { return {kGrid, law.element, ff, "HEMLForceField"}; }

/// HEML's mass-spring mode (HEML eq. (38)): a spring of 20 N/m per mesh edge, no material.
inline BodyParts springParts() { return {kGrid, "", " stiffness=\"20\"", "HEMLForceField"}; }

/// The parts of a HEML case: a device law by name, or "springs".
inline BodyParts caseParts(const std::string& name) { return name == "springs" ? springParts() : parts(deviceLaw(name)); }

/// Every device law's name and "springs".
inline std::vector<std::string> caseNames() {
    std::vector<std::string> out;
    for (const Law& l : deviceLaws()) out.push_back(l.name);
    out.push_back("springs");
    return out;
}

using MakeRunner = std::function<std::unique_ptr<cuda::StepRunner>(const cuda::StepSetup&, cuda::Precision)>;

/// The device kernels' forces (runner make(setup, precision)) against HEMLForceField's at a deformed
/// state, for every law and the springs, at scales 0.3, 1 and 3 (3: some elements below J0): 1e-12
/// relative in double, 1e-5 in float.
inline void forcesMatch(const MakeRunner& make) {
    const std::string name = GENERATE(from_range(caseNames()));
    const double scale = GENERATE(0.3, 1.0, 3.0);
    CAPTURE(name, scale);
    ForceProbe p = probeForces(scene(caseParts(name), ""), scale);
    REQUIRE(p.setup.form == cuda::StepSetup::Form::Edges);
    REQUIRE(p.setup.springs == (name == "springs"));
    REQUIRE(p.setup.nTets == 72);
    REQUIRE(p.setup.dN.empty());
    checkForces(make, p);
}

/// 1000 steps of every law and of the springs with the CudaStep `root` against HEMLForceField on
/// the CPU, with SemiImplicitEuler: to `tol` relative to the largest displacement.
inline void trajectoriesFollow(const std::string& root, double tol) {
    const std::string name = GENERATE(from_range(caseNames()));
    CAPTURE(name);
    const Pair r = runBoth(caseParts(name), "", "<SemiImplicitEuler damping=\"5\"/>", root, 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= tol);
    CHECK(r.moved > 1e-4);  // (a trajectory that stayed at rest would compare well too)
}

/// A Prony series relaxing either part, or both, of every law: 1000 steps against HEMLForceField,
/// or the same refusal (a part that carries a stress at rest, materials/RelaxationSplit.h) from the
/// CPU and the device step; tol as trajectoriesFollow.
inline void relaxedFollow(const std::string& root, double tol) {
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string apply = GENERATE(as<std::string>{}, "isochoric", "volumetric", "both");
    CAPTURE(law.name, apply);
    const std::string cpuError = initError(scene(parts(law), "", prony(apply)));
    if (!cpuError.empty()) {
        CHECK(initError(scene(parts(law), root, prony(apply))) == cpuError);
        return;
    }
    // (the laws with no volumetric term, IncompressibleNeoHookean and IncompressibleMooneyRivlin: with
    // their isochoric part relaxed, what is left of -2 C1 ln J has a negative bulk stiffness, and
    // the body collapses in volume, HEMLForceField on the CPU too, near step 600: compared over the
    // first 300 steps)
    const int steps = law.name.rfind("Incompressible", 0) == 0 ? 300 : 1000;
    const Pair r = runBoth(parts(law), prony(apply), "<SemiImplicitEuler damping=\"5\"/>", root, steps);
    CAPTURE(steps, sci(r.err));
    CHECK(r.err <= tol);
    CHECK(r.moved > 1e-4);
}

/// The group cases of GroupCases.h on HEML's tetrahedra (materials per group, fibre arrays): forces
/// at scales 1 and 3 against HEMLForceField's, 1e-12 in double and 1e-5 in float.
inline void groupForcesMatch(const MakeRunner& make) {
    const groups::GroupCase c = GENERATE(from_range(groups::groupCases()));
    const double scale = GENERATE(1.0, 3.0);
    CAPTURE(c.name, scale);
    BodyParts body = groups::groupParts(c, Mesh::Tets);
    body.forceField = "HEMLForceField";
    ForceProbe p = probeForces(scene(body, ""), scale);
    REQUIRE(p.setup.groups.size() == size_t(c.groups));
    checkForces(make, p);
}

/// 1000 steps of three groups with fibre arrays, with a Prony series or none, against HEMLForceField.
inline void groupsFollow(const std::string& root, double tol) {
    const bool relaxed = GENERATE(false, true);
    CAPTURE(relaxed);
    BodyParts body = groups::groupParts(groups::groupCase("three groups with fibre arrays"), Mesh::Tets);
    body.forceField = "HEMLForceField";
    const Pair r = runBoth(body, relaxed ? prony() : "", "<SemiImplicitEuler damping=\"5\"/>", root, 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= tol);
    CHECK(r.moved > 1e-4);
}

} // namespace cudatest::heml
