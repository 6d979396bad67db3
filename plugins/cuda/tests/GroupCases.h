#pragma once
// The cases of TLEDForceField's materials per mesh group and fibre directions per element
// (groupMaterials, fibreArray, fibreArray2) on the device step, on the cantilever read from a mesh
// file with group tags and fibre arrays: run through the emulation (TestCudaEmulation.cpp) and
// through real launches (TestCudaDevice.cpp) with the same checks, against TLEDForceField.
#include "CudaTestSupport.h"

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace cudatest::groups {

/// The law's material element named `name` (its example parameters, fibre directions included).
inline std::string material(const std::string& law, const std::string& name) {
    std::string e = deviceLaw(law).element;
    const size_t at = e.find("name=\"mat\"");
    REQUIRE(at != std::string::npos);
    return e.replace(at, 10, "name=\"" + name + "\"");
}

/// The fibre directions of cell c (tetrahedra, then hexahedra, as in the mesh's cell arrays): a0
/// (which = 0) or b0 (1), turning from cell to cell, of lengths between 0.5 and 2 (the force field
/// makes them unit), b0 never parallel to a0.
inline Vec3 cellFibre(int which, int c) {
    const double t = 0.7 * c + 0.3, length = 0.5 + 0.25 * (c % 7);
    const Vec3 a(std::cos(t), std::sin(t), 0.4 + 0.2 * std::cos(2.1 * c)), b(-std::sin(t), std::cos(t), 0.3 * std::sin(1.3 * c));
    return length * (which == 0 ? a : b);
}

/// The cantilever of `mesh` as a legacy VTK file (written once per run): the grid's 36 nodes, the
/// elements of cantileverElements, each cell's group tag (CellEntityIds) 1 + i for the columns i =
/// 0, 1 of cells and 3 + i in the top layer (k = 2), and the cell arrays 'fibres' (a0) and
/// 'fibres2' (b0) of cellFibre. Returns its path.
inline std::string meshFile(Mesh mesh) {
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("fascia_cuda_" + meshName(mesh) + "_" + std::to_string(getpid()) + ".vtk")).string();
    if (std::filesystem::exists(path)) return path;
    std::vector<std::array<int, 4>> tets;
    std::vector<std::array<int, 8>> hexes;
    std::vector<int> tetTag, hexTag;
    cantileverElements(mesh == Mesh::Hexes, mesh == Mesh::Mixed, tets, hexes, [&](int i, int, int k) {
        (tets.size() > tetTag.size() ? tetTag : hexTag).push_back(1 + i + (k == 2 ? 2 : 0));
    });
    const size_t nT = tets.size(), nH = hexes.size(), n = nT + nH;
    std::string out = "# vtk DataFile Version 3.0\ncantilever\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 36 double\n";
    char b[128];
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                std::snprintf(b, sizeof b, "%.17g %.17g %.17g\n", 0.01 * i, 0.01 * j, 0.01 * k);
                out += b;
            }
    out += "CELLS " + std::to_string(n) + " " + std::to_string(5 * nT + 9 * nH) + "\n";
    for (const auto& t : tets) out += "4 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + " " + std::to_string(t[3]) + "\n";
    for (const auto& h : hexes) {
        out += "8";
        for (int a : h) out += " " + std::to_string(a);
        out += "\n";
    }
    out += "CELL_TYPES " + std::to_string(n) + "\n";
    for (size_t c = 0; c < n; ++c) out += c < nT ? "10\n" : "12\n";
    out += "CELL_DATA " + std::to_string(n) + "\nSCALARS CellEntityIds int 1\nLOOKUP_TABLE default\n";
    for (int t : tetTag) out += std::to_string(t) + "\n";
    for (int t : hexTag) out += std::to_string(t) + "\n";
    for (int w = 0; w < 2; ++w) {
        out += w == 0 ? "VECTORS fibres double\n" : "VECTORS fibres2 double\n";
        for (size_t c = 0; c < n; ++c) {
            const Vec3 d = cellFibre(w, int(c));
            std::snprintf(b, sizeof b, "%.17g %.17g %.17g\n", d[0], d[1], d[2]);
            out += b;
        }
    }
    const std::string tmp = path + ".part";
    {
        std::ofstream f(tmp);
        f << out;
        REQUIRE(f.good());
    }
    std::filesystem::rename(tmp, path);
    // removed when the test program ends
    static struct Written {
        std::vector<std::string> paths;
        ~Written() {
            for (const std::string& p : paths) std::filesystem::remove(p);
        }
    } written;
    written.paths.push_back(path);
    return path;
}

/// A case of materials per group and fibres per element: the material elements and the
/// TLEDForceField's attributes, on the mesh file of meshFile.
struct GroupCase {
    std::string name, materials, ff;
    int groups = 1;  ///< the material groups the device step makes of it
};

/// The cases: fibre arrays with each law that reads them (a second array with the laws of two
/// fibres, alone for HolzapfelGasserOgden: its a0 is then the material's), and two and three
/// groups of different laws (with a fallback material), also with fibre arrays.
inline std::vector<GroupCase> groupCases() {
    const std::string fibres = " fibreArray=\"fibres\"", both = fibres + " fibreArray2=\"fibres2\"";
    const std::string three = material("NeoHookean", "a") + material("TransverselyIsotropic", "b") + material("HolzapfelGasserOgden", "c");
    return {
        {"TransverselyIsotropic with fibreArray", material("TransverselyIsotropic", "mat"), fibres, 1},
        {"Orthotropic with fibreArray and fibreArray2", material("Orthotropic", "mat"), both, 1},
        {"HolzapfelGasserOgden with fibreArray2 alone", material("HolzapfelGasserOgden", "mat"), " fibreArray2=\"fibres2\"", 1},
        {"three groups", three, " groupMaterials=\"1 @a 2 @b 3 @c 4 @a\"", 3},
        {"two groups, one the fallback material", material("CompressibleNeoHookean", "a") + material("Orthotropic", "b"),
         " material=\"@a\" groupMaterials=\"2 @b 4 @b\"" + both, 2},
        {"three groups with fibre arrays", three, " groupMaterials=\"1 @a 2 @b 3 @c 4 @a\"" + both, 3},
    };
}

/// The parts of a group case on the mesh file of `mesh`.
inline BodyParts groupParts(const GroupCase& c, Mesh mesh) {
    return BodyParts{"<MeshLoader name=\"loader\" filename=\"" + meshFile(mesh) + "\"/>", c.materials, c.ff};
}

/// The group case of that name.
inline GroupCase groupCase(const std::string& name) {
    for (const GroupCase& c : groupCases())
        if (c.name == name) return c;
    FAIL("no group case " << name);
    return {};
}


/// Every group case's internal forces at a deformed state (scales 1 and 3: some elements below J0),
/// on each mesh, from the runner make(setup, precision) against TLEDForceField's: 1e-12 relative in
/// double, 1e-5 in float; and the groups, lists and fibre rows the device step made of each case.
template <class MakeRunner>
void forcesMatch(MakeRunner&& make) {
    const GroupCase c = GENERATE(from_range(groupCases()));
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Hexes, Mesh::Mixed);
    const double scale = GENERATE(1.0, 3.0);
    CAPTURE(c.name, meshName(mesh), scale);
    ForceProbe p = probeForces(scene(groupParts(c, mesh), ""), scale);
    const cuda::StepSetup& s = p.setup;
    REQUIRE(s.groups.size() == size_t(c.groups));
    size_t listed = 0;
    for (const auto& g : s.groups) listed += g.tets.size() + g.hexes.size();
    CHECK(listed == (c.groups == 1 ? 0 : size_t(s.nTets + s.nHexes)));
    CHECK(s.fibresPerElement == (c.ff.find("fibreArray") != std::string::npos));
    if (s.fibresPerElement) CHECK(s.fa.size() + s.hfa.size() == 3 * size_t(s.nTets + s.nHexes));
    checkForces(make, p);
}

/// 1000 steps of the group cases with the CudaStep `root` against the CPU: fibre arrays on
/// tetrahedra, hexahedra and the mixed mesh, groups on tetrahedra and the mixed mesh, to `tol`
/// relative to the largest displacement.
inline void trajectoriesFollow(const std::string& root, double tol) {
    struct Run {
        std::string name;
        Mesh mesh;
    };
    const Run run = GENERATE(values<Run>({{"TransverselyIsotropic with fibreArray", Mesh::Tets},
                                          {"TransverselyIsotropic with fibreArray", Mesh::Hexes},
                                          {"Orthotropic with fibreArray and fibreArray2", Mesh::Mixed},
                                          {"HolzapfelGasserOgden with fibreArray2 alone", Mesh::Hexes},
                                          {"three groups", Mesh::Tets},
                                          {"three groups", Mesh::Mixed},
                                          {"two groups, one the fallback material", Mesh::Mixed},
                                          {"three groups with fibre arrays", Mesh::Tets},
                                          {"three groups with fibre arrays", Mesh::Mixed}}));
    CAPTURE(run.name, meshName(run.mesh));
    const Pair r = runBoth(groupParts(groupCase(run.name), run.mesh), "", "<SemiImplicitEuler damping=\"5\"/>", root, 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= tol);
    CHECK(r.moved > 1e-4);
}

/// The same with Prony series (one relaxing the isochoric part, or one per part): two groups
/// (CompressibleNeoHookean and Orthotropic, each with its own shift of s ln J between the parts,
/// materials/RelaxationSplit.h) with fibre arrays, on the mixed mesh.
inline void relaxedGroupsFollow(const std::string& root, double tol) {
    const std::string series = GENERATE(as<std::string>{}, "one", "two");
    CAPTURE(series);
    const Pair r = runBoth(groupParts(groupCase("two groups, one the fallback material"), Mesh::Mixed), series == "one" ? prony() : kTwoSeries,
                           "<SemiImplicitEuler damping=\"5\"/>", root, 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= tol);
    CHECK(r.moved > 1e-4);
}

/// The fibre arrays and the groups matter: the trajectory of the fibre array case leaves the one of
/// the same material with its own directions, and the one of the groups leaves the one of their
/// first material for all, by far more than the device's error (1000 steps, the mixed mesh).
inline void arraysAndGroupsMatter(const std::string& root, double tol) {
    const std::string loader = "<MeshLoader name=\"loader\" filename=\"" + meshFile(Mesh::Mixed) + "\"/>";
    const GroupCase fibres = groupCase("Orthotropic with fibreArray and fibreArray2"), three = groupCase("three groups");
    const std::vector<std::pair<BodyParts, BodyParts>> cases = {
        {groupParts(fibres, Mesh::Mixed), {loader, fibres.materials, ""}},
        {groupParts(three, Mesh::Mixed), {loader, three.materials, " material=\"@a\""}},
    };
    for (const auto& [own, uniform] : cases) {
        CAPTURE(own.ff);
        const Pair a = runBoth(own, "", "<SemiImplicitEuler damping=\"5\"/>", root, 1000);
        const Pair b = runBoth(uniform, "", "<SemiImplicitEuler damping=\"5\"/>", root, 1000);
        const double apart = displacementError(a.device, b.device, a.rest);
        CAPTURE(sci(apart), sci(a.err), sci(b.err));
        CHECK(apart >= 0.02);
        CHECK(a.err <= tol);
        CHECK(b.err <= tol);
    }
}

} // namespace cudatest::groups
