#pragma once
// The loads of the device step beyond a constant force: ConstantForce with load curves (CudaStep
// scales each curved load's force by c(t) in the node kernel). Run through the emulation
// (TestCudaLoads.cpp) and through real launches (TestCudaDevice.cpp) with the same checks.
#include "CudaTestSupport.h"

namespace cudatest::loads {

/// Two ConstantForce components with load curves (a ramp, and a curve that changes sign) beside
/// the scene's constant pull, on nodes of the free end and of the side.
inline const std::string kCurvedForces =
    "<ConstantForce name=\"ramped\" indices=\"30 31 32\" force=\"0 0.003 -0.002\" curve=\"ramp 0.01\"/>"
    "<ConstantForce name=\"swung\" indices=\"20 21\" force=\"0.004 0 0.001\" curve=\"linear 0 0  0.005 1  0.015 -1\"/>";

/// The scene with the loads of `body` follows the CPU over 1000 steps (with either integrator,
/// tetrahedra and the mixed mesh), and the loads matter: without them the trajectory ends far away.
inline void followsTheCpu(const std::string& body, const std::string& root, double tol) {
    const std::string integrator = GENERATE(as<std::string>{}, "<SemiImplicitEuler damping=\"5\"/>", "<CentralDifference damping=\"5\"/>");
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Mixed);
    CAPTURE(integrator, meshName(mesh));
    const Law law = deviceLaw("NeoHookean");
    const Pair r = runBoth(law, body, integrator, mesh, root, 1000);
    const Pair without = runBoth(law, "", integrator, mesh, root, 1000);
    const double apart = displacementError(without.device, r.cpu, r.rest);
    CAPTURE(sci(r.err), sci(apart));
    // (damped CentralDifference in double: the CPU's own rounding in x, about 7e-10; test_cuda_emulation)
    const bool central = integrator.find("Central") != std::string::npos;
    CHECK(r.err <= (central && tol < 1e-6 ? 5e-9 : tol));
    CHECK(apart >= 0.05);
}

/// The curved ConstantForce loads follow the CPU.
inline void curvedForcesFollowTheCpu(const std::string& root, double tol) { followsTheCpu(kCurvedForces, root, tol); }

/// Two SurfacePressure components: a pressure on the free end (z = 0.03) growing over 5 ms, and a
/// constant suction on the side x = 0.02 (triangles on the tetrahedral grid, quadrilaterals on the
/// hexahedral one, which the mixed mesh's grid is).
inline const std::string kPressures =
    "<SurfacePressure name=\"push\" nodeGroup=\"zmax\" pressure=\"40\" curve=\"ramp 0.005\"/>"
    "<SurfacePressure name=\"suck\" nodeGroup=\"xmax\" pressure=\"-15\"/>";

/// The pressures follow the CPU (triangles on the tetrahedral grid, quadrilaterals on the mixed mesh's).
inline void pressuresFollowTheCpu(const std::string& root, double tol) { followsTheCpu(kPressures, root, tol); }

/// The corner forces in node order (CudaStep forceOrder="node") give bitwise the forces and the
/// trajectory of the forces by element: TLED on the tetrahedral and the mixed mesh (hexahedra,
/// triangles and quadrilaterals under pressure) and HEML, with the pressures, a Prony series and the
/// lift (200 steps). make(setup, precision): a runner; rootOpen: the CudaStep element without "/>".
template <class MakeRunner>
void forceOrderIsBitwise(MakeRunner&& make, const std::string& rootOpen) {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    const std::string ff = GENERATE(as<std::string>{}, "TLEDForceField tets", "TLEDForceField mixed", "HEMLForceField tets");
    CAPTURE(precision, ff);
    const bool mixed = ff.find("mixed") != std::string::npos;
    BodyParts parts{"<GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"" +
                        std::string(mixed ? "hexahedra" : "tetrahedra6") + "\"/>",
                    deviceLaw("TransverselyIsotropic").element, mixed ? mixedElements() : "", ff.substr(0, ff.find(' '))};
    const std::string body = kPressures + kLift + prony();
    // one element pass, through runners
    ForceProbe p = probeForces(scene(parts, "", body), 1.0);
    REQUIRE(p.setup.nTris + p.setup.nQuads > 0);
    const cuda::Precision pr = precision == "float" ? cuda::Precision::Float : cuda::Precision::Double;
    std::vector<double> f[2];
    for (int k = 0; k < 2; ++k) {
        p.setup.forcesInNodeOrder = k == 1;
        CHECK(cuda::toArrays<double>(p.setup).sf.size() == (k == 1 ? 3 * p.setup.slots.size() : 0));
        auto runner = make(p.setup, pr);
        runner->setState(p.u, p.v);
        runner->elementPass();
        runner->internalForces(f[k]);
    }
    CHECK(f[1] == f[0]);
    // 200 steps through CudaStep
    const auto run = [&](const std::string& order) {
        auto sim = core::Simulation::fromString(
            scene(parts, rootOpen + " precision=\"" + precision + "\" forceOrder=\"" + order + "\"/>", body));
        sim->run(200);
        return std::pair{sim->state("mo").x(), sim->state("mo").v()};
    };
    const auto byElement = run("element"), byNode = run("node");
    CHECK(byNode.first == byElement.first);
    CHECK(byNode.second == byElement.second);
}

} // namespace cudatest::loads
