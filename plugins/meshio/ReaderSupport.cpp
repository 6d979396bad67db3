#include "ReaderSupport.h"

#include "fascia/base/Error.h"
#include "fascia/base/InputFile.h"
#include "fascia/base/Format.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

namespace fascia::meshio::detail {

namespace fs = std::filesystem;

const char* const kSupportedFormats =
    "supported are .msh (Gmsh ASCII 1, 2.2, 4.1), .vtk (VTK legacy), .vtu (VTK XML) and .node/.ele (TetGen)";

void fail(const std::string& file, int line, const std::string& message, std::vector<std::string> notes) {
    fascia::core::throwInputError(fascia::core::SourceLoc{file, line}, message, std::move(notes));
}

void failAtByte(const std::string& file, long long byte, const std::string& message, std::vector<std::string> notes) {
    fascia::core::throwInputError(fascia::core::SourceLoc{file, 0, byte}, message, std::move(notes));
}

std::string quoted(std::string_view s) {
    std::string out = "'";
    out.append(s.substr(0, 60));
    if (s.size() > 60) out += "...";
    return out + "'";
}

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (auto& c : ext) c = char(std::tolower((unsigned char)c));
    return ext;
}

std::string plural(long long n, const std::string& word) {
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

void checkReadable(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) {
        std::error_code ec2;
        const fs::path abs = fs::absolute(path, ec2);
        const bool relative = !ec2 && fs::path(path).is_relative();
        fail(path, 0, "mesh file '" + path + "' does not exist" +
                          (relative ? " (looked for " + abs.string() + ")" : std::string()) +
                          "; check the file name and the folder it is in");
    }
    if (fs::is_directory(st)) fail(path, 0, "'" + path + "' is a folder, not a mesh file");
    core::requireRegularFile(path, "mesh file", core::kMaxMeshFileBytes, {path, 0});  // no FIFO, device or giant
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        const int err = errno;
        fail(path, 0, "cannot open mesh file '" + path + "' for reading (" + std::strerror(err) +
                          "); check its permissions");
    }
}

size_t reserveHint(long long n) { return size_t(std::clamp<long long>(n, 0, 1 << 22)); }

std::string readWholeFile(const std::string& path, bool keepBom) {
    checkReadable(path);
    std::ifstream in(path, std::ios::binary);
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    std::string text;
    if (size > 0) {
        text.resize(size_t(size));
        in.read(text.data(), size);
        if (in.gcount() != size) fail(path, 0, "cannot read mesh file '" + path + "': read error after " +
                                                   std::to_string(in.gcount()) + " of " + std::to_string(size) + " bytes");
    }
    if (!keepBom && text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);  // UTF-8 byte-order mark
    return text;
}

} // namespace fascia::meshio::detail
