#pragma once
// Helpers of the surface tests: temporary files and small closed surfaces.
#include "fascia/surface/TriangleSurface.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace fascia::surface::test {

/// A file in a fresh temporary folder, removed with the object.
struct TempFile {
    std::filesystem::path path;
    TempFile(const std::string& name, const std::string& bytes) {
        static int counter = 0;
        const auto dir = std::filesystem::temp_directory_path() /
                         ("fascia_surface_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        std::filesystem::create_directories(dir);
        path = dir / name;
        std::ofstream(path, std::ios::binary) << bytes;
    }
    ~TempFile() {
        std::error_code ec;
        std::filesystem::remove_all(path.parent_path(), ec);
    }
    std::string str() const { return path.string(); }
};

/// The message of the input error that f throws ("" when none).
template <class F>
std::string inputError(F&& f) {
    try {
        f();
    } catch (const core::Error& e) {
        if (e.kind() == core::ErrorKind::Input) return e.what();
        return "not an input error: " + std::string(e.what());
    }
    return "";
}

/// The unit tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), faces outwards: volume 1/6.
inline Positions tetPoints() { return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}; }
inline Triangles tetFaces() { return {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}; }

/// An ASCII STL file of the given triangles.
inline std::string asciiStl(const Positions& p, const Triangles& t) {
    std::string s = "solid test\n";
    for (const auto& f : t) {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for (int k : f)
            s += "      vertex " + std::to_string(p[size_t(k)][0]) + " " + std::to_string(p[size_t(k)][1]) + " " +
                 std::to_string(p[size_t(k)][2]) + "\n";
        s += "    endloop\n  endfacet\n";
    }
    return s + "endsolid test\n";
}

/// A binary STL file of the given triangles; the header starts with `header`.
inline std::string binaryStl(const Positions& p, const Triangles& t, const std::string& header = "binary") {
    std::string s(80, ' ');
    s.replace(0, header.size(), header);
    const std::uint32_t n = std::uint32_t(t.size());
    s.append(reinterpret_cast<const char*>(&n), 4);
    for (const auto& f : t) {
        float v[12] = {0, 0, 0};
        for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 3; ++a) v[3 + 3 * c + a] = float(p[size_t(f[size_t(c)])][a]);
        s.append(reinterpret_cast<const char*>(v), sizeof v);
        s.append(2, '\0');  // attribute byte count
    }
    return s;
}

} // namespace fascia::surface::test
