// fascia-bench --suite contact: what a rigid tool's contact adds to a step (the target: a capsule on
// the 21k-tetrahedron abdomen-size mesh adds 10 % or less; docs/performance.md, "Contact"), side by side
// in one run.
#include "Bench.h"
#include "fascia/sim/Tool.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace fascia::bench {

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

/// The capsule of capsuleXml as a closed triangle surface (OBJ) in the same frame: tip centre at
/// the origin, the shaft along +x. Rings around x: a pole and `cap` rings on each hemisphere,
/// `shaft` - 1 rings between the equators, `around` points a ring: 2 around (2 cap + shaft - 1 + 1)
/// triangles (9,984 with the defaults: the 10k-triangle surface tool of docs/performance.md, "Contact"), wound outward.
void writeCapsuleObj(const std::string& path, int around = 48, int cap = 12, int shaft = 81) {
    const double pi = 3.14159265358979323846;
    std::vector<std::pair<double, double>> rings;  // (x, radius) from the tip's pole to the back's
    for (int k = 1; k <= cap; ++k) rings.push_back({-kRadius * std::cos(k * pi / (2 * cap)), kRadius * std::sin(k * pi / (2 * cap))});
    for (int j = 1; j < shaft; ++j) rings.push_back({kLength * j / shaft, kRadius});
    for (int k = 0; k < cap; ++k) rings.push_back({kLength + kRadius * std::sin(k * pi / (2 * cap)), kRadius * std::cos(k * pi / (2 * cap))});
    std::ofstream out(path);
    out.precision(12);
    out << "v " << -kRadius << " 0 0\n";
    for (const auto& [x, r] : rings)
        for (int j = 0; j < around; ++j)
            out << "v " << x << " " << r * std::cos(2 * pi * j / around) << " " << r * std::sin(2 * pi * j / around) << "\n";
    out << "v " << kLength + kRadius << " 0 0\n";
    const int n = int(rings.size()), last = 2 + n * around;  // OBJ indices from 1: the tip's pole is 1
    auto at = [&](int ring, int j) { return 2 + ring * around + (j % around); };
    for (int j = 0; j < around; ++j) {
        out << "f 1 " << at(0, j + 1) << " " << at(0, j) << "\n";
        for (int i = 0; i + 1 < n; ++i)
            out << "f " << at(i, j) << " " << at(i, j + 1) << " " << at(i + 1, j + 1) << "\nf " << at(i, j) << " " << at(i + 1, j + 1) << " "
                << at(i + 1, j) << "\n";
        out << "f " << at(n - 1, j) << " " << at(n - 1, j + 1) << " " << last << "\n";
    }
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

void runContactSuite(const Case& base) {
    const std::string organMesh = findMesh("organ_21436.msh");
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
            auto sim = build(plain, plain.threads);
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
            auto sim = build(capsule, capsule.threads);
            const size_t before = contactNodes(sim->state("state"));
            sim->run(base.steps);
            std::printf("{\"forcefield\": \"%s\", \"case\": \"capsule\", \"nodes_in_contact_after_settle\": %zu, "
                        "\"nodes_in_contact_after_%d_more_steps\": %zu, \"tool_force_z\": %.4g}\n",
                        ff, before, base.steps, contactNodes(sim->state("state")), sim->tool("probe").force()[2]);
        }
        // the same capsule as a 10k-triangle surface tool (its signed distance grid at the default
        // resolution, the exact closest triangle near the surface): a budget of 25 % (docs/performance.md, "Contact")
        const std::string obj =
            (std::filesystem::temp_directory_path() / ("fascia-bench-capsule-" + std::to_string(getpid()) + ".obj")).string();
        writeCapsuleObj(obj);
        Case surface = capsule;
        std::string xml = capsule.bodyExtra;
        xml.replace(xml.find("<CapsuleTool"), 12, "<SurfaceTool mesh=\"" + obj + "\"");
        for (const char* attr : {" radius=\"", " length=\"", " axis=\""}) {
            const size_t a = xml.find(attr), b = xml.find('"', a + std::string(attr).size());
            xml.erase(a, b + 1 - a);
        }
        surface.bodyExtra = xml;
        surface.label = "surface capsule";
        {
            auto sim = build(surface, surface.threads);
            sim->run(base.steps);
            std::printf("{\"forcefield\": \"%s\", \"case\": \"surface capsule\", \"nodes_in_contact\": %zu, \"tool_force_z\": %.4g}\n", ff,
                        contactNodes(sim->state("state")), sim->tool("probe").force()[2]);
        }
        runCases({plain, capsule, surface});
        std::filesystem::remove(obj);
    }
}

} // namespace fascia::bench
