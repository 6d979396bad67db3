// fascia-bench: times full explicit steps (forces, integration, constraints) of a force field on a
// mesh and prints one JSON object per case. See `fascia-bench --help`.
#include "BenchCase.h"
#include "fascia/sim/Simulation.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace fascia::core;
using fascia::Vec3;
namespace fs = std::filesystem;

namespace {

const char* kHelp = R"(fascia-bench: time full explicit steps of a force field

usage:
  fascia-bench [--forcefield HEML|TLED] [--material NAME] [--mesh FILE | --cube N]
               [--element tetrahedra6|tetrahedra5|hexahedra] [--steps N] [--threads T] [--repeat R]
               [--viscous] [--determinism]
  fascia-bench --suite [--steps N] [--repeat R]
  fascia-bench --overhead N [--steps N] [--repeat R]
  fascia-bench --load SCENE.xml [--repeat R]

  --forcefield    HEML (default) or TLED
  --material      a material component: CompressibleNeoHookean (default), StVenantKirchhoff,
                  NeoHookean, TransverselyIsotropic, ... (E = 3 kPa, nu = 0.45 where it applies)
  --mesh FILE     a mesh file (Gmsh, VTK, TetGen)
  --cube N        a generated unit cube of N x N x N cells (6 tetrahedra per cell by default)
  --steps N       timed steps per repeat (default 200)
  --threads T     OpenMP threads (default 2)
  --repeat R      timed repeats; the median is reported with min and max (default 5)
  --viscous       add a one-term ViscoelasticProny to the force field's node
  --determinism   also run with 1 thread and report whether positions are bitwise identical
  --suite [heml|tled|scaling|contact]
                  the standard sets of docs/performance.md: heml (default: HEML compressible
                  neo-Hookean and Saint Venant-Kirchhoff on the 4.4k and 21k organ meshes and a
                  2M-tetrahedron cube, 1 and 2 threads), tled (TLED neo-Hookean, transversely
                  isotropic and one Prony term on 20k and 200k tetrahedra, hexahedra against
                  tetrahedra; TLED beside HEML on the 21k organ mesh), scaling (HEML and TLED from
                  20k to 200k tetrahedra), contact (HEML and TLED on the 21k organ mesh without
                  a tool and with a capsule pressed into it and moving every step)
  --overhead N    per-step cost of the framework: a one-node scene with N trivial components
                  (ConstantForce) against the same scene with none
  --load SCENE    time to parse, build and initialise a scene (ms), median of the repeats

The cases of one suite line (the tled suite's four cases per size, the scaling suite's HEML and
TLED per size) run side by side: built first, then timed in rounds, one repeat of each per round;
step_time_vs_first and per_element_vs_first are medians over the rounds of the ratio to the first
case of the line, robust to a noisy machine.

Each case prints one JSON object: forcefield, material, mesh, elements, nodes, threads, precision,
steps, ms_per_step (median), ms_min, ms_max, ns_per_element_step, and forcefield_ns_per_element:
the force field's addForce alone, timed in the same rounds (its element loop and its own node
passes, without the integrator, the other force terms and the checks of a step), with
forcefield_per_element_vs_first beside the step ratios.
)";

using bench::Case;

std::string materialXml(const std::string& m) {
    std::string attrs = "youngModulus=\"3000\" poissonRatio=\"0.45\"";
    if (m == "IncompressibleNeoHookean") attrs = "C1=\"500\"";
    if (m == "IncompressibleMooneyRivlin") attrs = "C1=\"400\" C2=\"100\"";
    if (m == "CompressibleMooneyRivlin") attrs = "C1=\"400\" C2=\"100\" kappa=\"10000\"";
    if (m == "TransverselyIsotropic") attrs += " eta=\"2000\" direction=\"0 1 1\"";
    if (m == "Orthotropic") attrs += " eta=\"2000\" direction=\"0 1 0\" eta2=\"1000\" direction2=\"1 0 0\"";
    return "<" + m + " name=\"material\" " + attrs + "/>";
}

/// c with force field ff and the neo-Hookean material it is compared with: HEML's compressible
/// neo-Hookean (eq. (26)), TLED's neo-Hookean (scaling suite, and the tled suite's organ line)
Case sideBySide(const Case& c, const std::string& ff) {
    Case s = c;
    s.forcefield = ff;
    s.material = ff == "HEML" ? "CompressibleNeoHookean" : "NeoHookean";
    return s;
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
    s << "<Node name=\"root\" dt=\"1e-5\">\n  <Node name=\"body\">\n";
    if (!c.mesh.empty())
        s << "    <MeshLoader name=\"loader\" filename=\"" << fs::absolute(c.mesh).string() << "\"/>\n";
    else
        s << "    <GridMesh name=\"loader\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"" << c.cube << " " << c.cube << " "
          << c.cube << "\" element=\"" << c.element << "\"/>\n";
    s << "    <MechanicalObject name=\"state\"/>\n"
      << "    <LumpedMass density=\"1000\"/>\n"
      << "    " << materialXml(c.material) << "\n"
      << "    <" << c.forcefield << "ForceField name=\"ff\"/>\n";
    if (c.viscous) s << "    <ViscoelasticProny alpha=\"0.5\" tau=\"0.58\"/>\n";
    s << "    <SemiImplicitEuler/>\n"
      << "    <BoxROI name=\"base\" box=\"-1e9 -1e9 -1e9 1e9 1e9 " << (c.mesh.empty() ? "0.001" : "-0.04") << "\"/>\n"
      << "    <FixedConstraint indices=\"@base.indices\"/>\n"
      << c.bodyExtra << "  </Node>\n</Node>\n";
    return s.str();
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

std::unique_ptr<Simulation> build(const Case& c, int threads) {
    omp_set_num_threads(threads);
    auto sim = Simulation::fromString(sceneXml(c), "<bench>");
    // the time step must stay stable for the timed steps: use a fraction of the critical one
    const double crit = sim->criticalTimeStep();
    if (std::isfinite(crit)) sim->setDt(0.5 * crit);
    deform(sim->state("state"));
    if (c.settle > 0) sim->run(c.settle);
    return sim;
}

/// Times the cases side by side: every case is built and warmed up first, then the repeats run in
/// rounds (each round times every case once), so that a slow spell of a noisy machine hits all of
/// them alike. Beside its own median, each case after the first reports the median over the rounds
/// of its time divided by the first case's time in the same round (docs/performance.md, lesson 9).
void runCases(const std::vector<Case>& cs) {
    const size_t nc = cs.size();
    std::vector<std::unique_ptr<Simulation>> sims;
    std::vector<size_t> elements(nc), nodes(nc);
    std::vector<BaseForceField*> ffs(nc);
    for (size_t i = 0; i < nc; ++i) {
        sims.push_back(build(cs[i], cs[i].threads));
        auto* ff = dynamic_cast<BaseForceField*>(sims[i]->find("ff"));
        ffs[i] = ff;
        elements[i] = ff ? ff->elementCount() : 0;
        nodes[i] = sims[i]->state("state").size();
        sims[i]->run(5);  // warm-up
    }
    // full steps (ms), and the force field's addForce alone (ms per call): the element loop with
    // its own node passes, without the integrator, the other force terms and the checks
    std::vector<std::vector<double>> ms(nc), ratio(nc), msFF(nc), ratioFF(nc);
    std::vector<std::vector<double>> rounds(cs[0].repeat, std::vector<double>(nc)), roundsFF = rounds;
    std::vector<fascia::Positions> fScratch(nc);
    for (size_t i = 0; i < nc; ++i) fScratch[i].assign(nodes[i], Vec3::Zero());
    const auto since = [](std::chrono::steady_clock::time_point t0) {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    };
    for (int r = 0; r < cs[0].repeat; ++r)
        for (size_t j = 0; j < nc; ++j) {
            const size_t i = r % 2 == 0 ? j : nc - 1 - j;  // alternate the order: no case always runs first
            omp_set_num_threads(cs[i].threads);
            auto t0 = std::chrono::steady_clock::now();
            sims[i]->run(cs[i].steps);
            ms[i].push_back(since(t0) / cs[i].steps);
            rounds[size_t(r)][i] = ms[i].back();
            // (at the simulation's time: TLED's viscous history then recomputes the same step each
            // call; HEML's would recompute the open step's states at the current positions and so
            // change the trajectory: not timed alone with viscosity)
            if (!ffs[i] || (cs[i].viscous && cs[i].forcefield == "HEML")) continue;
            auto& st = sims[i]->state("state");
            t0 = std::chrono::steady_clock::now();
            for (int k = 0; k < cs[i].steps; ++k) ffs[i]->addForce(st, fScratch[i], sims[i]->time());
            msFF[i].push_back(since(t0) / cs[i].steps);
            roundsFF[size_t(r)][i] = msFF[i].back();
        }
    for (size_t r = 0; r < rounds.size(); ++r)
        for (size_t i = 1; i < nc; ++i) {
            ratio[i].push_back(rounds[r][i] / rounds[r][0]);
            if (roundsFF[r][0] > 0) ratioFF[i].push_back(roundsFF[r][i] / roundsFF[r][0]);
        }
    const auto median = [](std::vector<double> v) {
        if (v.empty()) return 0.0;
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    for (size_t i = 0; i < nc; ++i) {
        const Case& c = cs[i];
        const double med = median(ms[i]);
        const auto [fastest, slowest] = std::minmax_element(ms[i].begin(), ms[i].end());
        std::string extra = c.label.empty() ? "" : ", \"case\": \"" + c.label + "\"";
        char buf[240];
        const double perElement = double(elements[0]) / double(std::max<size_t>(1, elements[i]));
        if (i > 0) {
            // per element: the step-time ratio scaled by the element counts
            const double rq = median(ratio[i]);
            std::snprintf(buf, sizeof buf, ", \"step_time_vs_first\": %.4f, \"per_element_vs_first\": %.4f", rq, rq * perElement);
            extra = buf;
        }
        if (elements[i] && !msFF[i].empty()) {
            std::snprintf(buf, sizeof buf, ", \"forcefield_ns_per_element\": %.3f", median(msFF[i]) * 1e6 / double(elements[i]));
            extra += buf;
            if (i > 0 && !msFF[0].empty()) {
                std::snprintf(buf, sizeof buf, ", \"forcefield_per_element_vs_first\": %.4f", median(ratioFF[i]) * perElement);
                extra += buf;
            }
        }
        if (c.determinism) {
            auto a = build(c, 1), b = build(c, c.threads);
            omp_set_num_threads(1);  // the force fields read the thread count when they run
            a->run(50);
            omp_set_num_threads(c.threads);
            b->run(50);
            bool same = true;
            auto& xa = a->state("state").x();
            auto& xb = b->state("state").x();
            for (size_t k = 0; k < xa.size() && same; ++k) same = (xa[k].array() == xb[k].array()).all();
            extra += std::string(", \"bitwise_identical_1_vs_") + std::to_string(c.threads) + "_threads\": " + (same ? "true" : "false");
        }
        std::printf("{\"forcefield\": \"%s\", \"material\": \"%s\"%s, \"mesh\": \"%s\", \"elements\": %zu, \"nodes\": %zu, "
                    "\"threads\": %d, \"precision\": \"double\", \"steps\": %d, \"ms_per_step\": %.5f, \"ms_min\": %.5f, "
                    "\"ms_max\": %.5f, \"ns_per_element_step\": %.3f%s}\n",
                    c.forcefield.c_str(), c.material.c_str(), c.viscous ? ", \"viscoelastic\": true" : "",
                    c.mesh.empty() ? ("cube" + std::to_string(c.cube) + "-" + c.element).c_str() : fs::path(c.mesh).filename().c_str(),
                    elements[i], nodes[i], c.threads, c.steps, med, *fastest, *slowest,
                    elements[i] ? med * 1e6 / double(elements[i]) : 0.0, extra.c_str());
    }
    std::fflush(stdout);
}

void runCase(const Case& c) { runCases({c}); }

void runOverhead(int components, int steps, int repeat) {
    auto scene = [](int n) {
        std::ostringstream s;
        s << "<Node name=\"root\" dt=\"1e-3\">\n  <SemiImplicitEuler/>\n"
          << "  <MechanicalObject name=\"state\" position=\"0 0 0\"/>\n  <LumpedMass totalMass=\"1\"/>\n";
        for (int i = 0; i < n; ++i) s << "  <ConstantForce indices=\"0\" force=\"0 0 1e-9\"/>\n";
        s << "</Node>\n";
        return s.str();
    };
    std::vector<double> base, with;
    auto a = Simulation::fromString(scene(0), "<bench>");
    auto b = Simulation::fromString(scene(components), "<bench>");
    a->run(100);
    b->run(100);
    for (int r = 0; r < repeat; ++r) {
        for (auto* pair : {&base, &with}) {
            Simulation& sim = pair == &base ? *a : *b;
            const auto t0 = std::chrono::steady_clock::now();
            sim.run(steps);
            pair->push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps);
        }
    }
    std::sort(base.begin(), base.end());
    std::sort(with.begin(), with.end());
    const double mb = base[base.size() / 2], mw = with[with.size() / 2];
    std::printf("{\"case\": \"overhead\", \"components\": %d, \"steps\": %d, \"us_per_step_without\": %.4f, "
                "\"us_per_step_with\": %.4f, \"ns_per_component_step\": %.2f}\n",
                components, steps, mb, mw, (mw - mb) * 1e3 / components);
}

void runLoad(const std::string& scene, int repeat) {
    std::vector<double> ms;
    size_t nodes = 0, elements = 0;
    for (int r = 0; r < repeat; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        LoadOptions opts;
        opts.outputDir = (fs::temp_directory_path() / "fascia-bench-load").string();  // exporters write there
        auto sim = Simulation::fromFile(scene, opts);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        nodes = 0;
        elements = 0;
        for (auto& g : sim->groups()) {
            nodes += g.state->size();
            for (auto* ff : g.forceFields) elements += ff->elementCount();
        }
    }
    std::sort(ms.begin(), ms.end());
    std::printf("{\"case\": \"load\", \"scene\": \"%s\", \"nodes\": %zu, \"elements\": %zu, \"load_ms\": %.2f, "
                "\"load_ms_min\": %.2f, \"load_ms_max\": %.2f}\n",
                scene.c_str(), nodes, elements, ms[ms.size() / 2], ms.front(), ms.back());
}

int parseInt(const char* v, const char* opt) {
    if (!v) {
        std::cerr << "fascia-bench: " << opt << " needs a value\n";
        std::exit(1);
    }
    char* end;
    long x = std::strtol(v, &end, 10);
    if (*end || x <= 0) {
        std::cerr << "fascia-bench: " << opt << " needs a positive integer\n";
        std::exit(1);
    }
    return int(x);
}

} // namespace

int main(int argc, char** argv) {
    Case c;
    bool suite = false;
    std::string suiteName = "heml";
    int overhead = 0;
    std::string load;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
        auto str = [&](const char* opt) {
            const char* v = next();
            if (!v) {
                std::cerr << "fascia-bench: " << opt << " needs a value\n";
                std::exit(1);
            }
            return std::string(v);
        };
        if (a == "--help" || a == "-h") {
            std::cout << kHelp;
            return 0;
        } else if (a == "--forcefield") c.forcefield = str("--forcefield");
        else if (a == "--material") c.material = str("--material");
        else if (a == "--mesh") c.mesh = str("--mesh");
        else if (a == "--cube") c.cube = parseInt(next(), "--cube");
        else if (a == "--element") c.element = str("--element");
        else if (a == "--steps") c.steps = parseInt(next(), "--steps");
        else if (a == "--threads") c.threads = parseInt(next(), "--threads");
        else if (a == "--repeat") c.repeat = parseInt(next(), "--repeat");
        else if (a == "--viscous") c.viscous = true;
        else if (a == "--determinism") c.determinism = true;
        else if (a == "--suite") {
            suite = true;
            if (i + 1 < argc && argv[i + 1][0] != '-') suiteName = argv[++i];
        }
        else if (a == "--overhead") overhead = parseInt(next(), "--overhead");
        else if (a == "--load") load = str("--load");
        else {
            std::cerr << "fascia-bench: unknown option '" << a << "' (see --help)\n";
            return 1;
        }
    }
    if (c.forcefield != "HEML" && c.forcefield != "TLED") {
        std::cerr << "fascia-bench: --forcefield is HEML or TLED\n";
        return 1;
    }
    try {
        if (overhead > 0) {
            runOverhead(overhead, c.steps, c.repeat);
            return 0;
        }
        if (!load.empty()) {
            runLoad(load, c.repeat);
            return 0;
        }
        if (!suite) {
            if (c.mesh.empty() && c.cube == 0) c.cube = 16;
            runCase(c);
            return 0;
        }
        if (suiteName == "tled") {
            // the paper's cost claims side by side in one run: fibres, viscosity, hexahedra
            for (int cube : {15, 32}) {  // 20,250 and 196,608 tetrahedra
                std::vector<Case> group;
                for (auto [mat, visc] : {std::pair{"NeoHookean", false}, std::pair{"TransverselyIsotropic", false},
                                         std::pair{"NeoHookean", true}}) {
                    Case s = c;
                    s.forcefield = "TLED";
                    s.material = mat;
                    s.viscous = visc;
                    s.cube = cube;
                    s.steps = cube > 20 ? std::min(c.steps, 100) : c.steps;
                    group.push_back(s);
                }
                Case h = group[0];  // hexahedra with as many nodes
                h.element = "hexahedra";
                group.push_back(h);
                runCases(group);
            }
            // a Gmsh organ mesh, numbered as the mesher wrote it: TLED beside HEML (as in the scaling suite)
            std::vector<Case> organ;
            for (const char* ff : {"TLED", "HEML"}) {
                Case s = sideBySide(c, ff);
                s.mesh = findMesh("organ_21436.msh");
                s.cube = 0;
                organ.push_back(s);
            }
            runCases(organ);
            return 0;
        }
        if (suiteName == "contact") {
            bench::runContactSuite(c, findMesh("organ_21436.msh"), [](const Case& s) { return build(s, s.threads); }, runCases);
            return 0;
        }
        if (suiteName == "scaling") {
            for (int cube : {15, 20, 26, 32}) {  // 20k, 48k, 105k, 197k tetrahedra
                std::vector<Case> group;
                for (const char* ff : {"HEML", "TLED"}) {
                    Case s = sideBySide(c, ff);
                    s.cube = cube;
                    s.steps = cube > 20 ? std::min(c.steps, 100) : c.steps;
                    s.determinism = cube == 15;
                    group.push_back(s);
                }
                runCases(group);
            }
            return 0;
        }
        if (suiteName != "heml") {
            std::cerr << "fascia-bench: unknown suite '" << suiteName << "' (heml, tled, scaling or contact)\n";
            return 1;
        }
        for (const char* mat : {"CompressibleNeoHookean", "StVenantKirchhoff"})
            for (const std::string mesh : {"organ_4430.msh", "organ_21436.msh", "cube70"})
                for (int threads : {1, 2}) {
                    Case s = c;
                    s.material = mat;
                    s.threads = threads;
                    if (mesh == "cube70") {
                        s.mesh.clear();
                        s.cube = 70;  // 70^3 * 6 = 2.06M tetrahedra
                        s.steps = std::min(c.steps, 20);
                        s.repeat = std::min(c.repeat, 3);
                    } else {
                        s.mesh = findMesh(mesh);
                    }
                    runCase(s);
                }
        return 0;
    } catch (const Error& e) {
        std::cerr << e.what() << "\n";
        return e.kind() == ErrorKind::Input ? 2 : e.kind() == ErrorKind::Simulation ? 3 : 1;
    } catch (const std::exception& e) {
        std::cerr << "fascia-bench: " << e.what() << "\n";
        return 1;
    }
}
