// fascia-dump: runs scenes for a few steps and writes forces, energies, cell data, positions and
// velocities as hex floats (%a), so that a refactoring of the force fields can prove it changed no
// result: run it before and after, then compare the two files (--compare reports, per case and
// quantity, whether they are bitwise equal and the max relative difference).
// See `fascia-dump --help` (kHelp below) for the command line; tests/regression/CMakeLists.txt runs it.
//
// Cases: every scene under scenes/ (by its path), and inline variants covering HEML and TLED on
// tetrahedra and hexahedra, every built-in law, mass-spring, fibres per element and per group,
// materials per mesh group and Prony series, each with 1 and 2 threads.
#include "fascia/base/CommandLine.h"
#include "fascia/base/Error.h"
#include "fascia/base/InputFile.h"
#include "fascia/materials/BuiltinMaterials.h"
#include "fascia/sim/Simulation.h"

#include <omp.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace fascia::core;
using fascia::Positions;
using fascia::Vec3;
namespace fs = std::filesystem;

namespace {

struct Case {
    std::string name;
    std::string file;  ///< a scene file, or
    std::string xml;   ///< an inline scene
    int threads = 2;
    bool deform = false;  ///< start from a smooth deformation (inline cases)
};

/// A material element of law m: the parameters these dumps have always used for the first laws
/// (kept, so that dumps of older builds compare), else the law's example parameters (kExample).
std::string lawXml(const std::string& m) {
    static const std::map<std::string, std::string> kParams = {
        {"StVenantKirchhoff", "lambda=\"1500\" mu=\"1000\""},
        {"IncompressibleNeoHookean", "C1=\"500\""},
        {"IncompressibleMooneyRivlin", "C1=\"400\" C2=\"100\""},
        {"CompressibleNeoHookean", "C1=\"500\" mu=\"1000\" lambda=\"9000\""},
        {"CompressibleMooneyRivlin", "C1=\"400\" C2=\"100\" kappa=\"10000\""},
        {"NeoHookean", "youngModulus=\"3000\" poissonRatio=\"0.45\""},
        {"TransverselyIsotropic", "youngModulus=\"3000\" poissonRatio=\"0.45\" eta=\"2000\" direction=\"0 1 1\""},
        {"Orthotropic", "youngModulus=\"3000\" poissonRatio=\"0.45\" eta=\"2000\" direction=\"0 1 0\" eta2=\"1000\" direction2=\"1 0 0\""},
        {"HolzapfelGasserOgden", "mu=\"1000\" k1=\"3000\" k2=\"4\" dispersion=\"0.1\" bulkModulus=\"20000\" direction=\"1 0.2 0.3\" direction2=\"-0.2 1 0.4\""},
        {"ArrudaBoyce", "mu=\"1000\" lambdaM=\"2\" kappa=\"20000\""},
        {"UncoupledMooneyRivlin", "c1=\"400\" c2=\"150\" k=\"20000\""}};
    std::string a;
    if (auto it = kParams.find(m); it != kParams.end()) a = it->second;
    else
        for (const auto& [name, value] : fascia::materials::exampleParameters(m)) a += (a.empty() ? "" : " ") + name + "=\"" + value + "\"";
    return "<" + m + " name=\"mat\" " + a + "/>";
}

/// Every built-in law, from the one list (materials/BuiltinMaterials.h).
const std::vector<std::string>& laws() {
    static const std::vector<std::string> names = fascia::materials::builtinMaterialNames();
    return names;
}

/// An inline scene: a mesh line, the material lines and the force field line, on a cube fixed at z = 0.
std::string scene(const std::string& mesh, const std::string& materials, const std::string& ff, const std::string& extra = "") {
    return "<Node name=\"root\" dt=\"1e-4\">\n <Node name=\"body\">\n  " + mesh +
           "\n  <MechanicalObject name=\"state\"/>\n  <LumpedMass density=\"1000\"/>\n  " + materials + "\n  " + extra +
           "\n  " + ff + "\n  <SemiImplicitEuler/>\n  <BoxROI name=\"base\" box=\"-1 -1 -1 1 1 0.001\"/>\n"
           "  <FixedConstraint indices=\"@base.indices\"/>\n </Node>\n</Node>\n";
}

/// A cube of several element blocks (3072 tetrahedra, 729 hexahedra), so that threads share the work.
std::string grid(const std::string& element) {
    const std::string n = element == "hexahedra" ? "9 9 9" : "8 8 8";
    return "<GridMesh name=\"mesh\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"" + n + "\" element=\"" + element + "\"/>";
}

/// A VTK legacy file of a 3 x 3 x 3 cube (tetrahedra: 6 per cell, or hexahedra) with group ids
/// (CellEntityIds: 1 below z = 0.05, 2 above) and two fibre fields that vary per cell.
std::string writeVtk(const fs::path& dir, bool hexes) {
    const int n = 3;
    const double h = 0.1 / n;
    auto id = [&](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
    std::vector<std::vector<int>> cells;
    std::vector<int> groups;
    std::vector<Vec3> fa, fb;
    // the 6 tetrahedra around the main diagonal of a cell (corners by bits x, y, z)
    const int tets[6][4] = {{0, 1, 3, 7}, {0, 1, 7, 5}, {0, 5, 7, 4}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                int c[8];
                for (int b = 0; b < 8; ++b) c[b] = id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                const double t = 0.3 * i + 0.5 * j + 0.7 * k;
                auto add = [&](std::vector<int> cell, double s) {
                    cells.push_back(cell);
                    groups.push_back(k < 2 ? 1 : 2);
                    fa.push_back(Vec3(std::cos(t + s), std::sin(t + s), 0.5));
                    fb.push_back(Vec3(-std::sin(t + s), std::cos(t + s), 0.2));
                };
                if (hexes)
                    add({c[0], c[1], c[3], c[2], c[4], c[5], c[7], c[6]}, 0.0);
                else
                    for (int q = 0; q < 6; ++q) add({c[tets[q][0]], c[tets[q][1]], c[tets[q][2]], c[tets[q][3]]}, 0.1 * q);
            }
    const fs::path path = dir / (hexes ? "cube_hex.vtk" : "cube_tet.vtk");
    std::ofstream o(path);
    o.precision(17);
    o << "# vtk DataFile Version 3.0\nfascia-dump cube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS " << (n + 1) * (n + 1) * (n + 1)
      << " double\n";
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) o << i * h << " " << j * h << " " << k * h << "\n";
    const size_t per = hexes ? 8 : 4;
    o << "CELLS " << cells.size() << " " << cells.size() * (per + 1) << "\n";
    for (auto& c : cells) {
        o << per;
        for (int v : c) o << " " << v;
        o << "\n";
    }
    o << "CELL_TYPES " << cells.size() << "\n";
    for (size_t c = 0; c < cells.size(); ++c) o << (hexes ? 12 : 10) << "\n";
    o << "CELL_DATA " << cells.size() << "\nSCALARS CellEntityIds int 1\nLOOKUP_TABLE default\n";
    for (int g : groups) o << g << "\n";
    o << "FIELD FieldData 2\nfibres 3 " << cells.size() << " double\n";
    for (auto& v : fa) o << v[0] << " " << v[1] << " " << v[2] << "\n";
    o << "fibres2 3 " << cells.size() << " double\n";
    for (auto& v : fb) o << v[0] << " " << v[1] << " " << v[2] << "\n";
    return path.string();
}

std::vector<Case> allCases(const fs::path& tmp) {
    std::vector<Case> out;
    const fs::path scenes = fs::path(FASCIA_SOURCE_DIR) / "scenes";
    std::vector<std::string> files;
    for (auto& e : fs::recursive_directory_iterator(scenes))
        if (e.path().extension() == ".xml") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    for (auto& f : files) out.push_back({fs::relative(f, scenes).string(), f, "", 2, false});

    std::vector<std::pair<std::string, std::string>> inl;
    for (const std::string& law : laws()) {
        inl.push_back({std::string("heml_tet_") + law, scene(grid("tetrahedra6"), lawXml(law), "<HEMLForceField name=\"ff\"/>")});
        inl.push_back({std::string("tled_tet_") + law, scene(grid("tetrahedra6"), lawXml(law), "<TLEDForceField name=\"ff\"/>")});
        inl.push_back({std::string("tled_hex_") + law, scene(grid("hexahedra"), lawXml(law), "<TLEDForceField name=\"ff\"/>")});
    }
    inl.push_back({"heml_massSpring", scene(grid("tetrahedra5"), "", "<HEMLForceField name=\"ff\" stiffness=\"50\"/>")});
    const std::string nh = lawXml("NeoHookean");
    const std::string prony1 = "<ViscoelasticProny alpha=\"0.5\" tau=\"0.01\" apply=\"isochoric\"/>";
    const std::string prony2 = "<ViscoelasticProny alpha=\"0.3 0.2\" tau=\"0.01 0.002\" apply=\"both\"/>";
    const std::string pronyIV = prony1 + "\n  <ViscoelasticProny alpha=\"0.2\" tau=\"0.005\" apply=\"volumetric\"/>";
    inl.push_back({"heml_prony_iso", scene(grid("tetrahedra6"), nh, "<HEMLForceField name=\"ff\"/>", prony1)});
    inl.push_back({"heml_prony_both2", scene(grid("tetrahedra6"), nh, "<HEMLForceField name=\"ff\"/>", prony2)});
    inl.push_back({"heml_prony_vol", scene(grid("tetrahedra6"), nh, "<HEMLForceField name=\"ff\"/>",
                                           "<ViscoelasticProny alpha=\"0.2\" tau=\"0.005\" apply=\"volumetric\"/>")});
    for (const char* el : {"tetrahedra6", "hexahedra"}) {
        const std::string k = el[0] == 't' ? "tet" : "hex";
        inl.push_back({"tled_" + k + "_prony_iso", scene(grid(el), nh, "<TLEDForceField name=\"ff\"/>", prony1)});
        inl.push_back({"tled_" + k + "_prony_both2", scene(grid(el), nh, "<TLEDForceField name=\"ff\"/>", prony2)});
        inl.push_back({"tled_" + k + "_prony_iso_vol", scene(grid(el), nh, "<TLEDForceField name=\"ff\"/>", pronyIV)});
    }
    // fibres per element, groups
    const std::string vt = writeVtk(tmp, false), vh = writeVtk(tmp, true);
    const std::string loadT = "<MeshLoader name=\"mesh\" filename=\"" + vt + "\"/>";
    const std::string loadH = "<MeshLoader name=\"mesh\" filename=\"" + vh + "\"/>";
    const std::string ti = lawXml("TransverselyIsotropic"), ortho = lawXml("Orthotropic");
    const std::string fib = " fibreArray=\"fibres\" fibreArray2=\"fibres2\"";
    inl.push_back({"heml_fibreArray_TI", scene(loadT, ti, "<HEMLForceField name=\"ff\" fibreArray=\"fibres\"/>")});
    inl.push_back({"heml_fibreArray_Ortho", scene(loadT, ortho, "<HEMLForceField name=\"ff\"" + fib + "/>")});
    inl.push_back({"tled_tet_fibreArray_Ortho", scene(loadT, ortho, "<TLEDForceField name=\"ff\"" + fib + "/>")});
    inl.push_back({"tled_hex_fibreArray_TI", scene(loadH, ti, "<TLEDForceField name=\"ff\" fibreArray=\"fibres\"/>")});
    const std::string two = "<NeoHookean name=\"soft\" mu=\"1000\" kappa=\"10000\"/>\n  "
                            "<TransverselyIsotropic name=\"stiff\" mu=\"3000\" kappa=\"20000\" eta=\"4000\" direction=\"1 1 0\"/>";
    inl.push_back({"heml_groups", scene(loadT, two, "<HEMLForceField name=\"ff\" groupMaterials=\"1 @soft 2 @stiff\"/>")});
    inl.push_back({"tled_tet_groups", scene(loadT, two, "<TLEDForceField name=\"ff\" groupMaterials=\"1 @soft 2 @stiff\"/>")});
    inl.push_back({"tled_hex_groups_prony",
                   scene(loadH, two, "<TLEDForceField name=\"ff\" groupMaterials=\"1 @soft 2 @stiff\"/>", prony1)});
    for (auto& [name, xml] : inl)
        for (int t : {1, 2}) out.push_back({name + "_t" + std::to_string(t), "", xml, t, true});
    return out;
}

void deform(BaseMechanicalState& st) {
    Vec3 lo = st.x0()[0], hi = st.x0()[0];
    for (auto& p : st.x0()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double L = (hi - lo).maxCoeff(), k = 4 * M_PI / L, a = 0.05 / k;
    for (size_t i = 0; i < st.size(); ++i) {
        const Vec3& X = st.x0()[i];
        st.x()[i] = X + a * Vec3(std::sin(k * X[1]), std::sin(k * X[2]), std::sin(k * X[0]));
    }
}

void put(std::ostream& o, const std::string& label, const double* v, size_t n) {
    o << label << " " << n;
    char b[40];
    for (size_t i = 0; i < n; ++i) {
        std::snprintf(b, sizeof b, " %a", v[i]);
        o << b;
    }
    o << "\n";
}

void putPositions(std::ostream& o, const std::string& label, const Positions& p) {
    put(o, label, p.empty() ? nullptr : p.data()->data(), 3 * p.size());
}

/// A case loaded and ready to record: its simulation, its states and its force fields.
struct Running {
    std::unique_ptr<Simulation> sim;
    std::vector<BaseForceField*> ffs;
    std::vector<BaseMechanicalState*> states;
    int threads = 2;
    /// Runs `steps` more steps on the case's threads (a thread count is per process: set it each time,
    /// since --check-threads steps a 1-thread and a 2-thread case in turn).
    void advance(long steps) {
        omp_set_num_threads(threads);
        sim->run(steps);
    }
};

/// Loads a case (on its threads, which its force fields' blocks depend on) and deforms it if asked.
Running start(const Case& c, const fs::path& tmp) {
    omp_set_num_threads(c.threads);
    LoadOptions opt;
    opt.outputDir = (tmp / "out").string();
    fs::create_directories(opt.outputDir);
    Running r;
    r.threads = c.threads;
    r.sim = c.file.empty() ? Simulation::fromString(c.xml, c.name, tmp.string(), opt) : Simulation::fromFile(c.file, opt);
    r.ffs = r.sim->root().findAllInSubtree<BaseForceField>();
    r.states = r.sim->root().findAllInSubtree<BaseMechanicalState>();
    if (c.deform) {
        const double crit = r.sim->criticalTimeStep();
        if (std::isfinite(crit)) r.sim->setDt(0.5 * crit);
        for (auto* s : r.states) deform(*s);
    }
    return r;
}

/// Writes the records of step s: positions, velocities and forces of every state, then each force
/// field's energy (its stable time step at step 0) and cell data.
void record(Running& r, long s, std::ostream& o) {
    o << "step " << s << "\n";
    for (size_t i = 0; i < r.states.size(); ++i) {
        putPositions(o, "x" + std::to_string(i), r.states[i]->x());
        putPositions(o, "v" + std::to_string(i), r.states[i]->v());
        putPositions(o, "f" + std::to_string(i), r.states[i]->f());
    }
    for (size_t i = 0; i < r.ffs.size(); ++i) {
        BaseForceField& ff = *r.ffs[i];
        auto* st = ff.node()->findInContext<BaseMechanicalState>();
        if (!st) continue;
        const std::string p = "ff" + std::to_string(i) + ".";
        const double E = ff.potentialEnergy(*st);
        put(o, p + "energy", &E, 1);
        if (s == 0) {
            const double dt = ff.stableTimeStep(*st);
            put(o, p + "stableTimeStep", &dt, 1);
        }
        std::vector<CellField> cells;
        ff.cellData(*st, cells);
        for (auto& cf : cells) put(o, p + cf.name, cf.values.data(), cf.values.size());
    }
}

using CaseData = std::map<std::string, std::vector<double>>;  // "step label" -> values

/// A dump file, case by case. A line whose count of values is not what it holds (a truncated or
/// edited file) is a located input error: the count is never trusted for an allocation.
std::map<std::string, CaseData> readDump(const std::string& path) {
    std::map<std::string, CaseData> out;
    std::ifstream in(path);
    if (!in) throwInputError({path, 0}, "cannot read '" + path + "'");
    std::string line, cs, step;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        std::istringstream is(line);
        std::string label;
        if (!(is >> label)) continue;
        if (label == "case") { is >> cs; continue; }
        if (label == "step") { is >> step; continue; }
        size_t n = 0;
        std::vector<double> v;
        const bool counted = bool(is >> n);
        for (std::string t; is >> t;) v.push_back(std::strtod(t.c_str(), nullptr));
        if (!counted || v.size() != n)
            throwInputError({path, lineNo}, "'" + label + "' announces " + (counted ? std::to_string(n) : "no number of") +
                                                " values and holds " + std::to_string(v.size()) + ": not a whole fascia-dump file");
        out[cs][step + " " + label] = std::move(v);
    }
    return out;
}

/// Stress outputs of cellData (S, Cauchy, von Mises), reported apart from the trajectory (x, v, f,
/// energies, J, stable time step).
bool isStressOutput(const std::string& key) {
    for (const char* s : {".S", ".cauchyStress", ".vonMises"})
        if (key.size() >= std::strlen(s) && key.compare(key.size() - std::strlen(s), std::string::npos, s) == 0) return true;
    return false;
}

/// Per case: bitwise equal or not, and the max over its quantities of max_i |a_i - b_i| / max_i |a_i|,
/// for the trajectory and for the stress outputs.
int compare(const std::string& a, const std::string& b) {
    const auto A = readDump(a), B = readDump(b);
    int bad = 0;
    double worstAll = 0;
    for (auto& [cs, da] : A) {
        auto it = B.find(cs);
        if (it == B.end()) { std::printf("%-44s missing in %s\n", cs.c_str(), b.c_str()); ++bad; continue; }
        bool bitwise = true, trajectoryBitwise = true;
        double worst = 0, worstTrajectory = 0;
        std::string where;
        for (auto& [key, va] : da) {
            auto jt = it->second.find(key);
            if (jt == it->second.end() || jt->second.size() != va.size()) { bitwise = false; worst = INFINITY; where = key + " (missing)"; continue; }
            const auto& vb = jt->second;
            double scale = 0, diff = 0;
            for (size_t i = 0; i < va.size(); ++i) {
                scale = std::max(scale, std::abs(va[i]));
                const bool same = std::memcmp(&va[i], &vb[i], sizeof(double)) == 0 || (std::isnan(va[i]) && std::isnan(vb[i]));
                if (!same) {
                    bitwise = false;
                    diff = std::max(diff, std::abs(va[i] - vb[i]));
                }
            }
            const double rel = diff == 0 ? 0 : diff / (scale > 0 ? scale : 1.0);
            if (!isStressOutput(key)) {
                trajectoryBitwise = trajectoryBitwise && diff == 0;
                worstTrajectory = std::max(worstTrajectory, rel);
            }
            if (rel > worst || std::isnan(rel)) { worst = std::isnan(rel) ? INFINITY : rel; where = key; }
        }
        for (auto& [key, vb] : it->second)
            if (!da.count(key)) { bitwise = false; worst = INFINITY; where = key + " (extra)"; }
        worstAll = std::max(worstAll, worst);
        if (!(worst <= 1e-12)) ++bad;
        std::printf("%-44s %s  max rel diff %.3g%s%s  (trajectory: %s, %.3g)\n", cs.c_str(), bitwise ? "bitwise" : "differs", worst,
                    where.empty() ? "" : "  at ", where.c_str(), trajectoryBitwise ? "bitwise" : "differs", worstTrajectory);
    }
    for (auto& [cs, db] : B)
        if (!A.count(cs)) std::printf("%-44s only in %s\n", cs.c_str(), b.c_str());
    std::printf("cases: %zu, over 1e-12: %d, largest max rel diff %.3g\n", A.size(), bad, worstAll);
    return bad ? 1 : 0;
}

const char* kHelp = R"(fascia-dump: records of scenes as hex floats, to compare before and after a change

usage:
  fascia-dump [--steps N] [--every K] [--case NAME] OUT.txt
  fascia-dump [--steps N] [--every K] --scene FILE [--scene FILE ...] OUT.txt
  fascia-dump --compare BEFORE.txt AFTER.txt
  fascia-dump --check-threads [--steps N] [--every K] [--case NAME]
  fascia-dump --list [--scene FILE ...]
  fascia-dump --help

options:
  --steps N        steps per case (default 30)
  --every K        a record every K steps (default 10)
  --case NAME      only the cases whose name holds NAME
  --scene FILE     this scene file instead of the cases, started from the smooth deformation at half
                   the critical time step (a plugin's force field: set FASCIA_PLUGIN_PATH)
  --compare A B    per case and quantity: bitwise equal or not, and the max relative difference
                   (exit 1 when one is over 1e-12)
  --check-threads  the inline cases on 1 and 2 threads must agree bitwise
  --list           print the names of the cases

Cases: every scene under scenes/ (by its path), and inline variants of HEML and TLED (each with 1
and 2 threads). OUT.txt is written whole or not at all (OUT.txt.tmp, renamed at the end).
exit codes: 0 success; 1 a bad command line, an output that cannot be written, no case, a
difference (--compare, --check-threads); 2 a bad input file (a scene, a dump); 3 a failed run
)";

constexpr long kMaxSteps = INT_MAX;

struct Options {
    long steps = 30, every = 10;
    std::string only, outFile, compareA, compareB;
    std::vector<std::string> sceneFiles;
    bool list = false, checkThreads = false;
};

/// Parses the command line; --help prints the help and exits 0, a bad command line exits 1.
Options parseArgs(int argc, char** argv) {
    Options o;
    CommandLine cl("fascia-dump", argc, argv);
    while (cl.next()) {
        if (cl.isHelp()) {
            std::cout << kHelp;
            std::exit(0);
        } else if (cl.is("--compare")) {
            o.compareA = cl.path("two dump files: --compare BEFORE.txt AFTER.txt");
            o.compareB = cl.path("two dump files: --compare BEFORE.txt AFTER.txt");
        } else if (cl.is("--steps")) o.steps = cl.integer(0, kMaxSteps);
        else if (cl.is("--every")) o.every = cl.integer(1, kMaxSteps);
        else if (cl.is("--case")) o.only = cl.text();
        else if (cl.is("--scene")) o.sceneFiles.push_back(cl.path());
        else if (cl.is("--list")) o.list = true;
        else if (cl.is("--check-threads")) o.checkThreads = true;
        else if (cl.isOption()) cl.unknownOption();
        else if (o.outFile.empty()) o.outFile = cl.arg();
        else cl.fail("one output file at a time ('" + o.outFile + "' and '" + cl.arg() + "')");
    }
    if (o.compareA.empty() && !o.list && !o.checkThreads && o.outFile.empty())
        cl.fail("no output file: give OUT.txt (or --compare, --check-threads, --list)");
    return o;
}

/// Fails unless `bytes` more fit in the free space of the output file's folder (statvfs): a dump of
/// enormous --steps is refused after the first record of its first case, not when the disk is full.
void checkDisk(const Options& o, const std::string& caseName, double records, double bytesEach) {
    const fs::path dir = fs::absolute(o.outFile).parent_path();
    struct statvfs fsInfo {};
    if (::statvfs(dir.c_str(), &fsInfo) != 0) return;
    const double space = double(fsInfo.f_bavail) * double(fsInfo.f_frsize);
    if (records * bytesEach <= space) return;
    throw std::runtime_error("--steps " + std::to_string(o.steps) + " --every " + std::to_string(o.every) +
                             ": the records of case '" + caseName + "' do not fit on the disk\n(" +
                             CommandLine::realText(records) + " records of about " + bytesText(bytesEach) + " need " +
                             bytesText(records * bytesEach) + "; '" + dir.string() + "' has " + bytesText(space) + " free)");
}

/// The cases' records into OUT.txt, written whole or not at all; 1 when no case matches --case.
int dumpCases(const std::vector<Case>& cases, const Options& o, const fs::path& tmp) {
    OutputFile out(o.outFile);
    size_t ran = 0;
    for (auto& c : cases) {
        if (!o.only.empty() && c.name.find(o.only) == std::string::npos) continue;
        Running r = start(c, tmp);
        std::ostringstream first;
        first << "case " << c.name << "\n";
        record(r, 0, first);
        checkDisk(o, c.name, double(o.steps / o.every), double(first.str().size()));
        out.stream() << first.str();
        for (long s = o.every; s <= o.steps && out.good(); s += o.every) {
            r.advance(o.every);
            record(r, s, out.stream());
        }
        ++ran;
    }
    if (ran == 0) {
        std::fprintf(stderr, "fascia-dump: no case matches '%s' (see fascia-dump --list)\n", o.only.c_str());
        return 1;
    }
    out.commit();
    std::printf("fascia-dump: %zu cases, %ld steps each, written to %s\n", ran, o.steps, o.outFile.c_str());
    return 0;
}

/// --check-threads: each inline case's 1-thread and 2-thread runs (_t1 and _t2, one after the other in
/// the list) side by side, record by record: they must write the same bytes.
int checkThreads(const std::vector<Case>& cases, const Options& o, const fs::path& tmp) {
    std::map<std::string, bool> same;  // by the name without _t1 / _t2
    for (size_t i = 0; i + 1 < cases.size(); ++i) {
        const Case &a = cases[i], &b = cases[i + 1];
        const std::string base = a.name.substr(0, a.name.size() - 3);
        if (!a.file.empty() || a.threads != 1 || b.name != base + "_t2") continue;
        if (!o.only.empty() && a.name.find(o.only) == std::string::npos && b.name.find(o.only) == std::string::npos) continue;
        Running ra = start(a, tmp), rb = start(b, tmp);
        bool equal = true;
        for (long s = 0; s <= o.steps && equal; s += o.every) {
            if (s > 0) ra.advance(o.every), rb.advance(o.every);
            std::ostringstream ta, tb;
            record(ra, s, ta);
            record(rb, s, tb);
            equal = ta.str() == tb.str();
        }
        same[base] = equal;
    }
    int rc = 0;
    for (auto& [base, equal] : same) {
        std::printf("%-40s 1 vs 2 threads: %s\n", base.c_str(), equal ? "bitwise identical" : "DIFFERENT");
        if (!equal) rc = 1;
    }
    if (same.empty()) {
        std::fprintf(stderr, "fascia-dump: no case matches '%s'\n", o.only.c_str());
        rc = 1;
    }
    return rc;
}

/// The input files, checked before anything runs or is written: the scenes (as fascia-run reads
/// them) and the two dumps of --compare, which are read whole (at most half the memory each).
void checkInputs(const Options& o) {
    for (const std::string& f : o.sceneFiles) requireRegularFile(f, "scene file", kMaxSceneFileBytes, {f, 1});
    for (const std::string& f : {o.compareA, o.compareB})
        if (!f.empty()) requireRegularFile(f, "dump file", std::uintmax_t(memoryBudgetBytes() / 2), {f, 0});
}

} // namespace

int main(int argc, char** argv) {
    const Options o = parseArgs(argc, argv);
    fs::path tmp;
    int rc = 0;
    try {
        checkInputs(o);
        if (!o.compareA.empty()) return compare(o.compareA, o.compareB);
        if (!o.list && !o.checkThreads) requireOutputFile(o.outFile);
        tmp = fs::temp_directory_path() / ("fascia-dump-" + std::to_string(::getpid()));
        fs::create_directories(tmp);
        std::vector<Case> cases;
        for (const std::string& f : o.sceneFiles) cases.push_back({f, f, "", 2, true});
        if (o.sceneFiles.empty()) cases = allCases(tmp);
        if (o.list)
            for (auto& c : cases) std::cout << c.name << "\n";
        else if (o.checkThreads)
            rc = checkThreads(cases, o, tmp);
        else
            rc = dumpCases(cases, o, tmp);
    } catch (const Error& e) {
        std::cout.flush();
        std::fprintf(stderr, "%s\n", e.what());
        rc = e.kind() == ErrorKind::Input ? 2 : e.kind() == ErrorKind::Simulation ? 3 : 1;
    } catch (const std::exception& e) {
        std::cout.flush();
        std::fprintf(stderr, "fascia-dump: %s\n", e.what());
        rc = 1;
    }
    std::error_code ec;
    if (!tmp.empty()) fs::remove_all(tmp, ec);
    return rc;
}
