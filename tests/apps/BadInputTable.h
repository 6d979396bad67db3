#pragma once
/// What the two bad-input tables' tests share (tests/apps/badinput/catalogue.txt, run by
/// TestBadInputCatalogue.cpp, and programs.txt, run by TestProgramCommandLines.cpp): reading a table
/// of " | "-separated columns, replacing the places that differ between machines, and the check that
/// a run left its workspace as it found it.
#include "FasciaRunWorkspace.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace fasciaruntest {

inline std::string trim(const std::string& s) {
    const size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

/// s cut at every sep (at most maxParts parts, the last one holding the rest), each part trimmed.
inline std::vector<std::string> split(const std::string& s, const std::string& sep, size_t maxParts = 0) {
    std::vector<std::string> out;
    size_t at = 0;
    while (maxParts == 0 || out.size() + 1 < maxParts) {
        const size_t next = s.find(sep, at);
        if (next == std::string::npos) break;
        out.push_back(trim(s.substr(at, next - at)));
        at = next + sep.size();
    }
    out.push_back(trim(s.substr(at)));
    return out;
}

/// s with every `from` replaced by `to`.
inline std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
    if (from.empty()) return s;
    for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
    return s;
}

/// One line of a table: its line number and its columns.
struct TableRow {
    int line = 0;
    std::vector<std::string> fields;
};

/// Every row of a table of `columns` columns, in file order; blank lines and '#' comments are
/// skipped, and a line of another width fails the test that reads it.
inline std::vector<TableRow> readTable(const std::filesystem::path& file, size_t columns) {
    std::ifstream in(file);
    REQUIRE(in.good());
    std::vector<TableRow> rows;
    int n = 0;
    for (std::string line; std::getline(in, line);) {
        ++n;
        if (trim(line).empty() || trim(line)[0] == '#') continue;
        INFO(file.filename().string() << ":" << n << ": " << line);
        TableRow r{n, split(line, " | ", columns)};
        REQUIRE(r.fields.size() == columns);
        rows.push_back(r);
    }
    return rows;
}

/// Every file and folder under w (relative paths), but the run's own stdout and stderr.
inline std::set<std::string> snapshot(const Workspace& w) {
    std::set<std::string> out;
    std::error_code ec;
    for (auto it = std::filesystem::recursive_directory_iterator(w.dir(), ec); it != std::filesystem::recursive_directory_iterator();
         it.increment(ec)) {
        const std::string rel = std::filesystem::relative(it->path(), w.dir(), ec).string();
        if (rel != ".stdout" && rel != ".stderr") out.insert(rel);
    }
    return out;
}

/// Checks that w holds what it held before a run: nothing left behind, nothing removed.
inline void checkUntouched(const Workspace& w, const std::set<std::string>& before) {
    const std::set<std::string> after = snapshot(w);
    std::vector<std::string> left;
    for (const auto& f : after)
        if (!before.count(f)) left.push_back(f);
    INFO("left behind: " << (left.empty() ? std::string("nothing") : left.front()));
    CHECK(left.empty());
    CHECK(after == before);  // nothing removed either
}

} // namespace fasciaruntest
