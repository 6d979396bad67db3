// fascia-bench --suite contact: what a rigid tool's contact adds to a step (issue 14: a capsule on
// the 21k-tetrahedron abdomen-size mesh adds 10 % or less), side by side in one run.
#include "BenchCase.h"
#include "fascia/sim/Tool.h"

#include <cstdio>
#include <sstream>

namespace bench {

namespace {

constexpr int kSettle = 300;    // steps before the warm-up: the tool is pressed in during the first 200
constexpr int kPress = 200;     // steps to press the tool in from touching
constexpr int kSlide = 5000;    // then it slides across the surface, reaching kSlideBy at this step
constexpr double kRadius = 0.016, kLength = 0.1, kDepth = 0.02, kSlideBy = 0.01;  // m

/// A capsule lying along x across the top of the body (the node of highest z at rest), pressed
/// kDepth into it over kPress steps, then rolled across it along y, a little every step (a
/// palpation with the instrument's shaft), frictionless.
std::string capsuleXml(const fascia::Vec3& top, double dt) {
    std::ostringstream s;
    s.precision(9);
    const fascia::Vec3 touch = top + fascia::Vec3(-kLength / 2, 0, kRadius), pressed = touch - fascia::Vec3(0, 0, kDepth);
    const fascia::Vec3 slid = pressed + fascia::Vec3(0, kSlideBy, 0);
    s << "    <CapsuleTool name=\"probe\" radius=\"" << kRadius << "\" length=\"" << kLength << "\" axis=\"1 0 0\" keyTimes=\"0 "
      << kPress * dt << " " << kSlide * dt << "\" keyPositions=\"" << touch.transpose() << "  " << pressed.transpose() << "  "
      << slid.transpose() << "\"/>\n";
    return s.str();
}

/// The nodes with a contact force: a reaction on a node that no fixed constraint holds (the bench
/// fixes the nodes below z = -0.04 m).
size_t contactNodes(const fascia::core::BaseMechanicalState& st) {
    size_t n = 0;
    for (size_t i = 0; i < st.size(); ++i)
        if (st.x0()[i][2] > -0.04 && i < st.reaction().size() && !st.reaction()[i].isZero()) ++n;
    return n;
}

} // namespace

void runContactSuite(const Case& base, const std::string& organMesh, const BuildCase& build, const RunCases& run) {
    for (const char* ff : {"HEML", "TLED"}) {
        Case plain = base;
        plain.forcefield = ff;
        plain.material = plain.forcefield == "HEML" ? "CompressibleNeoHookean" : "NeoHookean";
        plain.mesh = organMesh;
        plain.cube = 0;
        plain.settle = kSettle;
        plain.label = "no tool";
        // the time step and the top of the body, from the case without a tool
        fascia::Vec3 top;
        double dt;
        {
            auto sim = build(plain);
            const auto& st = sim->state("state");
            top = st.x0()[0];
            for (const fascia::Vec3& p : st.x0())
                if (p[2] > top[2]) top = p;
            dt = sim->dt();
        }
        Case capsule = plain;
        capsule.bodyExtra = capsuleXml(top, dt);
        capsule.label = "capsule";
        {
            auto sim = build(capsule);
            const size_t before = contactNodes(sim->state("state"));
            sim->run(base.steps);
            std::printf("{\"forcefield\": \"%s\", \"case\": \"capsule\", \"nodes_in_contact_after_settle\": %zu, "
                        "\"nodes_in_contact_after_%d_more_steps\": %zu, \"tool_force_z\": %.4g}\n",
                        ff, before, base.steps, contactNodes(sim->state("state")), sim->tool("probe").force()[2]);
        }
        // TODO(issue 14): a SurfaceTool case (a 10k-triangle closed surface, mesh="...", its SDF grid)
        // beside these once plugins/contact has the class: the 25 % budget
        run({plain, capsule});
    }
}

} // namespace bench
