// Runs Fascia's conformance harness on the example's force field and material:
// forces = -grad(energy), zero force at rest, invariance under rigid motions; the Yeoh law's
// derivatives against finite differences, in HEMLForceField and TLEDForceField alike; the force
// field's forces bitwise the same with 1 and 2 threads, and with its tetrahedra from the mesh
// source in the node, from mesh= or from tetrahedra=.
#include "fascia/materials/Conformance.h"
#include "fascia/sim/Simulation.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

namespace conf = fascia::materials::conformance;

static std::string scene(const std::string& body) {
    return std::string("<Node name=\"root\" dt=\"1e-4\">\n  <RequiredPlugin name=\"") + EXAMPLE_PLUGIN_FILE + "\"/>\n"
           "  <GridMesh min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"2 2 2\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n  <LumpedMass density=\"1000\"/>\n" + body + "</Node>\n";
}

static int failures = 0;
static void expect(bool ok, const char* what, double value) {
    std::printf("%-60s %-4s %.3g\n", what, ok ? "ok" : "FAIL", value);
    failures += ok ? 0 : 1;
}

static void checkField(const std::string& body, const std::string& label) {
    auto sim = fascia::core::Simulation::fromString(scene(body), "<conformance>");
    auto* ff = dynamic_cast<fascia::core::BaseForceField*>(sim->find("ff"));
    auto r = conf::checkForceField(*ff, sim->state("state"));
    expect(r.gradientError < 1e-7, (label + ": force = -grad E").c_str(), r.gradientError);
    expect(r.restForce < 1e-12, (label + ": zero force at rest").c_str(), r.restForce);
    expect(r.rotationError < 1e-10, (label + ": rigid-motion invariance").c_str(), r.rotationError);
}

// forces on a 12 x 12 x 12 grid (8640 tetrahedra: 9 element blocks), deformed, with T threads and
// the force field's attributes attrs
static fascia::Positions forcesWith(int threads, const std::string& attrs = "") {
    omp_set_num_threads(threads);
    auto sim = fascia::core::Simulation::fromString(
        std::string("<Node name=\"root\" dt=\"1e-4\">\n  <RequiredPlugin name=\"") + EXAMPLE_PLUGIN_FILE + "\"/>\n"
        "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"12 12 12\"/>\n  <MechanicalObject name=\"state\"/>\n"
        "  <CorotationalTetForceField name=\"ff\" youngModulus=\"5000\" poissonRatio=\"0.4\"" + attrs + "/>\n</Node>\n",
        "<threads>");
    auto& st = sim->state("state");
    for (size_t i = 0; i < st.size(); ++i) {
        const fascia::Vec3& X = st.x0()[i];
        st.x()[i] = X + 0.004 * fascia::Vec3(std::sin(60 * X[1]), std::sin(60 * X[2]), std::sin(60 * X[0]));
    }
    fascia::Positions f(st.size(), fascia::Vec3::Zero());
    dynamic_cast<fascia::core::BaseForceField*>(sim->find("ff"))->addForce(st, f, 0.0);
    return f;
}

int main() {
    try {
        checkField("  <CorotationalTetForceField name=\"ff\" youngModulus=\"5000\" poissonRatio=\"0.4\"/>\n", "CorotationalTetForceField");
        const std::string yeoh = "  <Yeoh name=\"mat\" C10=\"1000\" C20=\"300\" C30=\"50\" kappa=\"20000\"/>\n";
        checkField(yeoh + "  <HEMLForceField name=\"ff\"/>\n", "Yeoh in HEMLForceField");
        checkField(yeoh + "  <TLEDForceField name=\"ff\"/>\n", "Yeoh in TLEDForceField");
        auto sim = fascia::core::Simulation::fromString(scene(yeoh), "<conformance>");
        auto* mat = dynamic_cast<fascia::materials::BaseMaterial*>(sim->find("mat"));
        for (double J : {0.7, 1.0, 1.3}) {
            auto r = conf::checkLawDerivatives(*mat, fascia::materials::Invariants{3.4, 3.9, J, 1, 1});
            expect(r.maxRelError < 1e-7, ("Yeoh: derivatives by central differences, J = " + std::to_string(J)).c_str(), r.maxRelError);
        }
        expect(conf::restStressResidual(*mat) < 1e-12, "Yeoh: stress-free at rest", conf::restStressResidual(*mat));
        const fascia::Positions f1 = forcesWith(1), f2 = forcesWith(2);
        double largest = 0;
        for (const auto& v : f1) largest = std::max(largest, v.norm());
        expect(largest > 0 && std::memcmp(f1.data(), f2.data(), f1.size() * sizeof(f1[0])) == 0,
               "CorotationalTetForceField: same forces with 1 and 2 threads", largest);
        const fascia::Positions fm = forcesWith(2, " mesh=\"@grid.mesh\""), ft = forcesWith(2, " tetrahedra=\"@grid.tetrahedra\"");
        expect(std::memcmp(f1.data(), fm.data(), f1.size() * sizeof(f1[0])) == 0 &&
                   std::memcmp(f1.data(), ft.data(), f1.size() * sizeof(f1[0])) == 0,
               "CorotationalTetForceField: same forces by mesh= and tetrahedra=", largest);
        std::string both;
        try {
            forcesWith(1, " mesh=\"@grid.mesh\" tetrahedra=\"@grid.tetrahedra\"");
        } catch (const std::exception& e) {
            both = e.what();
        }
        expect(both.find("not both") != std::string::npos, "CorotationalTetForceField: mesh= and tetrahedra= together are an error", 0);
    } catch (const std::exception& e) {
        std::printf("error: %s\n", e.what());
        return 1;
    }
    std::printf("%d failure(s)\n", failures);
    return failures ? 1 : 0;
}
