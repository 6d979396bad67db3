// fascia-bench: the scene of a case (Bench.h).
#include "Bench.h"

#include <omp.h>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace fascia::bench {

using namespace fascia::core;
namespace fs = std::filesystem;

namespace {

std::string materialXml(const std::string& m) {
    std::ostringstream ep;
    ep << "youngModulus=\"" << kYoung << "\" poissonRatio=\"" << kPoisson << "\"";
    std::string attrs = ep.str();
    if (m == "IncompressibleNeoHookean") attrs = "C1=\"500\"";
    if (m == "IncompressibleMooneyRivlin") attrs = "C1=\"400\" C2=\"100\"";
    if (m == "CompressibleMooneyRivlin") attrs = "C1=\"400\" C2=\"100\" kappa=\"10000\"";
    if (m == "TransverselyIsotropic") attrs += " eta=\"2000\" direction=\"0 1 1\"";
    if (m == "Orthotropic") attrs += " eta=\"2000\" direction=\"0 1 0\" eta2=\"1000\" direction2=\"1 0 0\"";
    return "<" + m + " name=\"material\" " + attrs + "/>";
}

/// A smooth, deterministic deformation so that every element works (no rest-state shortcut): two
/// waves across the body, with strains of a few per cent whatever the mesh size.
void deform(BaseMechanicalState& st) {
    Vec3 lo = st.x0()[0], hi = st.x0()[0];
    for (auto& p : st.x0()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double L = (hi - lo).maxCoeff(), k = 4 * M_PI / L, a = 0.03 / k;  // strain amplitude a k = 3 %
    for (size_t i = 0; i < st.size(); ++i) {
        const Vec3& X = st.x0()[i];
        st.x()[i] = X + a * Vec3(std::sin(k * X[1]), std::sin(k * X[2]), std::sin(k * X[0]));
    }
}

} // namespace

Case sideBySide(const Case& c, const std::string& ff) {
    Case s = c;
    s.forcefield = ff;
    s.material = ff == "HEML" ? "CompressibleNeoHookean" : "NeoHookean";
    return s;
}

Case referenceCase(const Case& c) {
    Case r = sideBySide(c, "TLED");  // its mesh and material: TLED's neo-Hookean
    r.reference = true;
    r.viscous = false;
    return r;
}

std::string findMesh(const std::string& name) {
    for (const std::string& dir : {std::string("."), std::string("scenes/meshes"), std::string(FASCIA_SOURCE_DIR) + "/scenes/meshes"}) {
        fs::path p = fs::path(dir) / name;
        if (fs::exists(p)) return p.string();
    }
    return name;
}

std::string sceneXml(const Case& c) {
    std::ostringstream s;
    s << "<Node name=\"root\" dt=\"1e-5\">\n";
    if (!c.device.empty())
        s << "  <CudaStep precision=\"" << c.precision << "\"" << (c.device == "emulate" ? " emulate=\"true\"" : "")
          << (c.block > 0 ? " blockSize=\"" + std::to_string(c.block) + "\"" : "")
          << (c.forceOrder.empty() ? "" : " forceOrder=\"" + c.forceOrder + "\"") << "/>\n";
    s << "  <Node name=\"body\">\n";
    if (!c.mesh.empty())
        s << "    <MeshLoader name=\"loader\" filename=\"" << fs::absolute(c.mesh).string() << "\"/>\n";
    else
        s << "    <GridMesh name=\"loader\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"" << c.cube << " " << c.cube << " "
          << c.cube << "\" element=\"" << c.element << "\"/>\n";
    s << "    <MechanicalObject name=\"state\"/>\n"
      << "    <LumpedMass density=\"1000\"/>\n"
      << "    " << materialXml(c.material) << "\n"
      << "    <" << c.forcefield << "ForceField name=\"ff\""
      << (c.precision == "double" || !c.device.empty() ? "" : " precision=\"" + c.precision + "\"")
      << (c.nodeBuffers.empty() || c.forcefield != "TLED" ? "" : " nodeBuffers=\"" + c.nodeBuffers + "\"") << "/>\n";
    if (c.viscous) s << "    <ViscoelasticProny alpha=\"0.5\" tau=\"0.58\"/>\n";
    s << "    <SemiImplicitEuler/>\n"
      << "    <BoxROI name=\"base\" box=\"-1e9 -1e9 -1e9 1e9 1e9 " << (c.mesh.empty() ? "0.001" : "-0.04") << "\"/>\n"
      << "    <FixedConstraint indices=\"@base.indices\"/>\n"
      << c.bodyExtra << "  </Node>\n</Node>\n";
    return s.str();
}

std::unique_ptr<Simulation> build(const Case& c, int threads) {
    omp_set_num_threads(threads);
    auto sim = Simulation::fromString(sceneXml(c), "<bench>");
    // the time step must stay stable for the timed steps: use a fraction of the critical one
    const double crit = sim->criticalTimeStep();
    if (std::isfinite(crit)) sim->setDt(0.5 * crit);
    // (on a device, no snapshot of the state every 100 steps: each one brings the state back)
    if (!c.device.empty()) sim->setSnapshotEvery(0);
    deform(sim->state("state"));
    if (c.settle > 0) sim->run(c.settle);
    return sim;
}

} // namespace fascia::bench
