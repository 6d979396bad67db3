// fascia-dump: runs scenes for a few steps and writes forces, energies, cell data, positions and
// velocities as hex floats (%a), so that a refactoring of the force fields can prove it changed no
// result: run it before and after, then compare the two files (--compare reports, per case and
// quantity, whether they are bitwise equal and the max relative difference).
//
//   fascia-dump [--steps N] [--every K] [--case NAME] [--list] OUT.txt
//   fascia-dump --compare BEFORE.txt AFTER.txt
//   fascia-dump --check-threads [--case NAME]    (1 and 2 threads must agree bitwise)
//   fascia-dump [--steps N] [--every K] --scene FILE [--scene FILE ...] OUT.txt
//       (those scene files instead of the cases, each started from the smooth deformation at half
//       the critical time step: for a plugin's force field, with FASCIA_PLUGIN_PATH set)
//
// Cases: every scene under scenes/ (by its path), and inline variants covering HEML and TLED on
// tetrahedra and hexahedra, every built-in law, mass-spring, fibres per element and per group,
// materials per mesh group and Prony series, each with 1 and 2 threads.
#include "fascia/base/Error.h"
#include "fascia/sim/Simulation.h"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
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

std::string lawXml(const std::string& m) {
    std::string a = "youngModulus=\"3000\" poissonRatio=\"0.45\"";
    if (m == "StVenantKirchhoff") a = "lambda=\"1500\" mu=\"1000\"";
    if (m == "IncompressibleNeoHookean") a = "C1=\"500\"";
    if (m == "IncompressibleMooneyRivlin") a = "C1=\"400\" C2=\"100\"";
    if (m == "CompressibleNeoHookean") a = "C1=\"500\" mu=\"1000\" lambda=\"9000\"";
    if (m == "CompressibleMooneyRivlin") a = "C1=\"400\" C2=\"100\" kappa=\"10000\"";
    if (m == "TransverselyIsotropic") a += " eta=\"2000\" direction=\"0 1 1\"";
    if (m == "Orthotropic") a += " eta=\"2000\" direction=\"0 1 0\" eta2=\"1000\" direction2=\"1 0 0\"";
    if (m == "HolzapfelGasserOgden")
        a = "mu=\"1000\" k1=\"3000\" k2=\"4\" dispersion=\"0.1\" bulkModulus=\"20000\" direction=\"1 0.2 0.3\" direction2=\"-0.2 1 0.4\"";
    if (m == "ArrudaBoyce") a = "mu=\"1000\" lambdaM=\"2\" kappa=\"20000\"";
    if (m == "UncoupledMooneyRivlin") a = "c1=\"400\" c2=\"150\" k=\"20000\"";
    return "<" + m + " name=\"mat\" " + a + "/>";
}

const char* kLaws[] = {"StVenantKirchhoff",      "IncompressibleNeoHookean", "IncompressibleMooneyRivlin",
                       "CompressibleNeoHookean", "CompressibleMooneyRivlin", "NeoHookean",
                       "TransverselyIsotropic",  "Orthotropic",              "HolzapfelGasserOgden",
                       "ArrudaBoyce",            "UncoupledMooneyRivlin"};

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
    for (const char* law : kLaws) {
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

/// Runs one case and writes its records.
void runCase(const Case& c, int steps, int every, const fs::path& tmp, std::ostream& o) {
    omp_set_num_threads(c.threads);
    LoadOptions opt;
    opt.outputDir = (tmp / "out").string();
    fs::create_directories(opt.outputDir);
    auto sim = c.file.empty() ? Simulation::fromString(c.xml, c.name, tmp.string(), opt) : Simulation::fromFile(c.file, opt);
    std::vector<BaseForceField*> ffs = sim->root().findAllInSubtree<BaseForceField>();
    std::vector<BaseMechanicalState*> states = sim->root().findAllInSubtree<BaseMechanicalState>();
    if (c.deform) {
        const double crit = sim->criticalTimeStep();
        if (std::isfinite(crit)) sim->setDt(0.5 * crit);
        for (auto* s : states) deform(*s);
    }
    o << "case " << c.name << "\n";
    for (int s = 0; s <= steps; s += every) {
        if (s > 0) sim->run(every);
        o << "step " << s << "\n";
        for (size_t i = 0; i < states.size(); ++i) {
            putPositions(o, "x" + std::to_string(i), states[i]->x());
            putPositions(o, "v" + std::to_string(i), states[i]->v());
            putPositions(o, "f" + std::to_string(i), states[i]->f());
        }
        for (size_t i = 0; i < ffs.size(); ++i) {
            BaseForceField& ff = *ffs[i];
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
}

struct Record {
    std::vector<double> v;
};
using CaseData = std::map<std::string, std::vector<double>>;  // "step label" -> values

std::map<std::string, CaseData> readDump(const std::string& path) {
    std::map<std::string, CaseData> out;
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::string line, cs, step;
    while (std::getline(in, line)) {
        std::istringstream is(line);
        std::string label;
        is >> label;
        if (label == "case") { is >> cs; continue; }
        if (label == "step") { is >> step; continue; }
        size_t n = 0;
        is >> n;
        std::vector<double> v(n);
        for (size_t i = 0; i < n; ++i) {
            std::string t;
            is >> t;
            v[i] = std::strtod(t.c_str(), nullptr);
        }
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

} // namespace

int main(int argc, char** argv) {
    int steps = 30, every = 10;
    std::string only, outFile;
    std::vector<std::string> sceneFiles;
    bool list = false, checkThreads = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--compare" && i + 2 < argc) return compare(argv[i + 1], argv[i + 2]);
        if (a == "--steps" && i + 1 < argc) steps = std::atoi(argv[++i]);
        else if (a == "--every" && i + 1 < argc) every = std::atoi(argv[++i]);
        else if (a == "--case" && i + 1 < argc) only = argv[++i];
        else if (a == "--scene" && i + 1 < argc) sceneFiles.push_back(argv[++i]);
        else if (a == "--list") list = true;
        else if (a == "--check-threads") checkThreads = true;
        else outFile = a;
    }
    const fs::path tmp = fs::temp_directory_path() / ("fascia-dump-" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    int rc = 0;
    try {
        std::vector<Case> cases;
        for (const std::string& f : sceneFiles) cases.push_back({f, f, "", 2, true});
        if (sceneFiles.empty()) cases = allCases(tmp);
        if (list) {
            for (auto& c : cases) std::cout << c.name << "\n";
        } else if (checkThreads) {
            // the inline cases in pairs (_t1, _t2): all but positions' origin the same, bitwise
            std::map<std::string, std::string> byBase[2];
            for (auto& c : cases) {
                if (c.file.size() || (!only.empty() && c.name.find(only) == std::string::npos)) continue;
                std::ostringstream o;
                Case d = c;
                d.name = "x";
                runCase(d, steps, every, tmp, o);
                byBase[c.threads - 1][c.name.substr(0, c.name.size() - 3)] = o.str();
            }
            for (auto& [base, text] : byBase[0]) {
                const bool same = byBase[1][base] == text;
                std::printf("%-40s 1 vs 2 threads: %s\n", base.c_str(), same ? "bitwise identical" : "DIFFERENT");
                if (!same) rc = 1;
            }
            if (byBase[0].empty()) { std::fprintf(stderr, "no case matches '%s'\n", only.c_str()); rc = 1; }
        } else {
            if (outFile.empty()) { std::fprintf(stderr, "usage: fascia-dump [--steps N] [--every K] [--case NAME] OUT.txt | --compare A B\n"); return 2; }
            std::ofstream o(outFile);
            size_t ran = 0;
            for (auto& c : cases) {
                if (!only.empty() && c.name.find(only) == std::string::npos) continue;
                runCase(c, steps, every, tmp, o);
                ++ran;
            }
            std::printf("fascia-dump: %zu cases, %d steps each, written to %s\n", ran, steps, outFile.c_str());
            if (ran == 0) rc = 1;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fascia-dump: %s\n", e.what());
        rc = 1;
    }
    fs::remove_all(tmp);
    return rc;
}
