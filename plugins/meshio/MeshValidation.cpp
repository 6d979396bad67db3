#include "MeshValidation.h"
#include "ReaderSupport.h"

#include "fascia/base/Error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <type_traits>
#include <utility>

namespace fascia::meshio {
namespace detail {
namespace {

std::string elementName(const ElementOrigin& o, bool hex, size_t i) {
    const auto& numbers = hex ? o.hexNumber : o.tetNumber;
    const char* kind = hex ? "hexahedron" : "tetrahedron";
    if (i < numbers.size()) return o.elementWord + " " + std::to_string(numbers[i]) + " (a " + kind + ")";
    return std::string(kind) + " " + std::to_string(i) + " (0-based)";
}

/// Where the file has item i: at bytes[i] (a BINARY file), on lines[i], or nowhere known (line 0).
core::SourceLoc placeOf(const std::string& file, const std::vector<int>& lines, const std::vector<long long>& bytes,
                        size_t i) {
    if (i < bytes.size()) return {file, 0, bytes[i]};
    return {file, i < lines.size() ? lines[i] : 0};
}

core::SourceLoc elementPlace(const ElementOrigin& o, bool hex, size_t i) {
    return placeOf(o.elementFile, hex ? o.hexLine : o.tetLine, hex ? o.hexByte : o.tetByte, i);
}

template <size_t N>
std::string nodeListText(const ElementOrigin& o, const std::array<int, N>& e) {
    std::string s;
    for (size_t k = 0; k < N; ++k) s += (k ? " " : "") + nodeName(o, e[k]);
    return s;
}

template <size_t N>
double longestEdgeCubed(const Positions& p, const std::array<int, N>& e) {
    double l2 = 0;
    if constexpr (N == 4) {
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) l2 = std::max(l2, (p[size_t(e[a])] - p[size_t(e[b])]).squaredNorm());
    } else {
        static const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                         {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
        for (const auto& ed : edges) l2 = std::max(l2, (p[size_t(e[ed[0]])] - p[size_t(e[ed[1]])]).squaredNorm());
    }
    return l2 * std::sqrt(l2);
}

template <class Group>
void normalizeGroup(Group& g, size_t n, const char* what) {
    if (g.size() == n) return;
    if (g.empty()) {
        g.assign(n, 0);
        return;
    }
    throw fascia::core::Error(fascia::core::ErrorKind::Internal, {},
                              std::string("mesh has ") + std::to_string(g.size()) + " " + what + " group tags for " +
                                  std::to_string(n) + " elements");
}

} // namespace

void validate(MeshData& mesh, const ElementOrigin& o, const ReadOptions& opt, ReadReport& report) {
    normalizeGroup(mesh.tetrahedronGroup, mesh.tetrahedra.size(), "tetrahedron");
    normalizeGroup(mesh.hexahedronGroup, mesh.hexahedra.size(), "hexahedron");
    normalizeGroup(mesh.triangleGroup, mesh.triangles.size(), "triangle");

    if (mesh.tetrahedra.empty() && mesh.hexahedra.empty()) {
        std::string found;
        if (!mesh.triangles.empty()) found = plural((long long)mesh.triangles.size(), "triangle");
        for (const auto& [kind, n] : report.skipped) found += (found.empty() ? "" : ", ") + plural(n, kind);
        fail(o.elementFile, 0,
             "'" + o.elementFile + "' has no volume elements (tetrahedra or hexahedra)" +
                 (found.empty() ? std::string(" and no elements at all") : "; it has " + found) +
                 ": a deformable body needs a volume mesh of linear tetrahedra or hexahedra (e.g. gmsh -3, "
                 "element order 1)");
    }

    const int nPoints = int(mesh.points.size());
    auto checkNodes = [&](const auto& elems, const char* kind, auto lineOf, auto nameOf) {
        for (size_t i = 0; i < elems.size(); ++i)
            for (int v : elems[i])
                if (v < 0 || v >= nPoints)
                    core::throwInputError(lineOf(i),
                         nameOf(i) + " names node " + std::to_string(v) + ", but the mesh has " +
                             plural(nPoints, "node") + " (valid " + kind + " node indices are 0 to " +
                             std::to_string(nPoints - 1) + "); fix the element's node list");
    };
    checkNodes(mesh.tetrahedra, "tetrahedron", [&](size_t i) { return elementPlace(o, false, i); },
               [&](size_t i) { return elementName(o, false, i); });
    checkNodes(mesh.hexahedra, "hexahedron", [&](size_t i) { return elementPlace(o, true, i); },
               [&](size_t i) { return elementName(o, true, i); });
    checkNodes(mesh.triangles, "triangle", [&](size_t) { return core::SourceLoc{o.elementFile, 0}; },
               [&](size_t i) { return "triangle " + std::to_string(i) + " (0-based)"; });

    for (size_t i = 0; i < mesh.points.size(); ++i) {
        const Vec3& x = mesh.points[i];
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
            core::throwInputError(placeOf(o.nodeFile, o.nodeLine, o.nodeByte, i),
                 "node " + nodeName(o, int(i)) + " has a non-finite coordinate (" + formatNumber(x[0], 6) + " " +
                     formatNumber(x[1], 6) + " " + formatNumber(x[2], 6) + "); every coordinate must be a finite number");
    }

    constexpr double kDegenerate = 1e-12;
    auto checkVolumes = [&](auto& elems, bool hex) {
        const char* kind = hex ? "hexahedra" : "tetrahedra";
        long long inverted = 0;
        size_t firstInverted = 0;
        double firstVolume = 0;
        for (size_t i = 0; i < elems.size(); ++i) {
            auto& e = elems[i];
            double v;
            if constexpr (std::tuple_size_v<std::decay_t<decltype(e)>> == 4)
                v = tetrahedronSignedVolume(mesh.points[size_t(e[0])], mesh.points[size_t(e[1])],
                                            mesh.points[size_t(e[2])], mesh.points[size_t(e[3])]);
            else
                v = hexahedronVolume(mesh.points, e);
            const double l3 = longestEdgeCubed(mesh.points, e);
            if (!(std::abs(v) > kDegenerate * l3))
                core::throwInputError(elementPlace(o, hex, i),
                     elementName(o, hex, i) + " is degenerate: its volume is " + formatNumber(v, 6) +
                         ", zero relative to its longest edge cubed (" + formatNumber(l3, 6) + "); its nodes (" +
                         nodeListText(o, e) + ") are repeated, coincide or lie in one plane: "
                         "remove or re-mesh this element");
            if (v < 0) {
                if (inverted++ == 0) {
                    firstInverted = i;
                    firstVolume = v;
                }
                if (opt.fixOrientation) {
                    if constexpr (std::tuple_size_v<std::decay_t<decltype(e)>> == 4)
                        std::swap(e[2], e[3]);
                    else
                        for (int k = 0; k < 4; ++k) std::swap(e[size_t(k)], e[size_t(k + 4)]);
                }
            }
        }
        if (inverted == 0) return;
        if (opt.fixOrientation) {
            report.flippedElements += int(inverted);
            return;
        }
        std::vector<std::string> notes;
        if (inverted > 1)
            notes.push_back(std::to_string(inverted) + " of " + std::to_string(elems.size()) + " " + kind +
                            " are inverted");
        core::throwInputError(elementPlace(o, hex, firstInverted),
             elementName(o, hex, firstInverted) + " is inverted: its signed volume is " + formatNumber(firstVolume, 6) +
                 " < 0 with its nodes in the file's order (" + nodeListText(o, elems[firstInverted]) +
                 "); reorder its nodes, or set fixOrientation to flip inverted elements when loading",
             std::move(notes));
    };
    checkVolumes(mesh.tetrahedra, false);
    checkVolumes(mesh.hexahedra, true);
}

} // namespace detail

double tetrahedronSignedVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

double hexahedronVolume(const std::array<Vec3, 8>& x) {
    // The volume is the integral of det J over the unit cube. Each column of J is bilinear in the two
    // other parametric coordinates, so det J has degree <= 2 in each coordinate and the 2x2x2 Gauss
    // rule integrates it exactly, warped faces included.
    static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
    double volume = 0;
    for (double u : g)
        for (double v : g)
            for (double w : g) {
                const double q[3] = {u, v, w};
                Mat3 J = Mat3::Zero();
                for (int i = 0; i < 8; ++i) {
                    double f[3], df[3];  // 1-D shape factor and its derivative per direction
                    for (int k = 0; k < 3; ++k) {
                        f[k] = corner[i][k] ? q[k] : 1.0 - q[k];
                        df[k] = corner[i][k] ? 1.0 : -1.0;
                    }
                    J.col(0) += x[size_t(i)] * (df[0] * f[1] * f[2]);
                    J.col(1) += x[size_t(i)] * (f[0] * df[1] * f[2]);
                    J.col(2) += x[size_t(i)] * (f[0] * f[1] * df[2]);
                }
                volume += J.determinant() / 8.0;
            }
    return volume;
}

double hexahedronVolume(const Positions& points, const std::array<int, 8>& hex) {
    std::array<Vec3, 8> x;
    for (size_t i = 0; i < 8; ++i) x[i] = points[size_t(hex[i])];
    return hexahedronVolume(x);
}

double totalVolume(const MeshData& mesh) {
    double v = 0;
    for (const auto& t : mesh.tetrahedra)
        v += tetrahedronSignedVolume(mesh.points[size_t(t[0])], mesh.points[size_t(t[1])], mesh.points[size_t(t[2])],
                                     mesh.points[size_t(t[3])]);
    for (const auto& h : mesh.hexahedra) v += hexahedronVolume(mesh.points, h);
    return v;
}

void validateMesh(MeshData& mesh, const std::string& file, const ReadOptions& opt, ReadReport* report) {
    ReadReport local;
    detail::ElementOrigin origin;
    origin.nodeFile = origin.elementFile = file;
    detail::validate(mesh, origin, opt, report ? *report : local);
}

} // namespace fascia::meshio
