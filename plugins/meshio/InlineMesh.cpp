#include "InlineMesh.h"
#include "MeshReaders.h"
#include "fascia/surface/BoundaryFaces.h"

#include <algorithm>
#include <sstream>

namespace fascia::meshio {

namespace {
/// "name: i j k; other: l m" -> name -> sorted unique indices; `bad` says what is wrong ("" when fine).
std::map<std::string, IndexList> parseGroups(const std::string& text, size_t nodes, std::string& bad) {
    std::map<std::string, IndexList> out;
    std::stringstream all(text);
    std::string part;
    while (std::getline(all, part, ';')) {
        if (part.find_first_not_of(" \t\n") == std::string::npos) continue;
        const auto colon = part.find(':');
        std::string name = colon == std::string::npos ? "" : part.substr(0, colon);
        name.erase(0, name.find_first_not_of(" \t\n"));
        name.erase(name.find_last_not_of(" \t\n") + 1);
        if (name.empty()) {
            bad = "group \"" + part + "\" has no name (write \"name: i j k\")";
            return {};
        }
        std::stringstream ids(part.substr(colon + 1));
        IndexList& g = out[name];
        std::string word;
        while (ids >> word) {
            char* end = nullptr;
            const long i = std::strtol(word.c_str(), &end, 10);
            if (*end != '\0' || i < 0 || size_t(i) >= nodes) {
                bad = "group '" + name + "': '" + word + "' is no node index in [0, " + std::to_string(nodes) + ")";
                return {};
            }
            g.push_back(int(i));
        }
        std::sort(g.begin(), g.end());
        g.erase(std::unique(g.begin(), g.end()), g.end());
    }
    return out;
}
} // namespace

void InlineMesh::init() {
    MeshData mesh;
    mesh.points = m_points.get();
    mesh.tetrahedra = m_tets.get();
    mesh.hexahedra = m_hexes.get();
    if (mesh.tetrahedra.empty() && mesh.hexahedra.empty())
        fail(m_points, "the mesh has no element: give tetrahedra or hexahedra");
    std::string bad;
    mesh.nodeGroups = parseGroups(m_groups.get(), mesh.points.size(), bad);
    if (!bad.empty()) fail(m_groups, bad);
    ReadOptions opt;
    opt.fixOrientation = m_fixOrientation.get();
    ReadReport report;
    try {
        validateMesh(mesh, loc().file, opt, &report);
    } catch (const core::Error& e) {
        fail(e.message(), e.notes());
    }
    if (report.flippedElements > 0) warn("flipped " + std::to_string(report.flippedElements) + " inverted element(s)");
    m_boundary = surface::boundaryTriangles(mesh);
    m_mesh.set(std::move(mesh));
    m_positions.view(&m_mesh.get().points);
}

} // namespace fascia::meshio
