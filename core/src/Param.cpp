#include "fascia/base/Component.h"
#include "fascia/base/Format.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace fascia::core {

namespace {

/// Splits on whitespace and commas.
std::vector<std::string> tokens(const std::string& text) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : text) {
        if (std::isspace((unsigned char)c) || c == ',') {
            if (!cur.empty()) out.push_back(std::move(cur)), cur.clear();
        } else {
            cur.push_back(c);
        }
    }
    if (!cur.empty()) out.push_back(std::move(cur));
    return out;
}

bool parseDouble(const std::string& s, double& v) {
    if (s.empty()) return false;
    char* end = nullptr;
    errno = 0;
    v = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && errno != ERANGE;
}

bool parseInt(const std::string& s, int& v) {
    auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

std::string checkNumber(double v, const ParamSpec& spec) {
    if (!std::isfinite(v)) return "is not a finite number";
    if (spec.lo && (spec.loExclusive ? !(v > *spec.lo) : !(v >= *spec.lo))) return "is outside " + spec.rangeText();
    if (spec.hi && (spec.hiExclusive ? !(v < *spec.hi) : !(v <= *spec.hi))) return "is outside " + spec.rangeText();
    return {};
}

template <class Seq>
std::string checkEach(const Seq& values, const ParamSpec& spec) {
    size_t i = 0;
    for (double v : values) {
        auto p = checkNumber(v, spec);
        if (!p.empty()) return "entry " + std::to_string(i) + " (" + formatNumber(v, 12) + ") " + p;
        ++i;
    }
    return {};
}

std::string checkCount(size_t n, const ParamSpec& spec) {
    if (spec.fixedCount && n != *spec.fixedCount)
        return "has " + std::to_string(n) + " entries, expected " + std::to_string(*spec.fixedCount);
    return {};
}

template <class T, size_t N>
bool parseIndexTuples(const std::string& text, std::vector<std::array<T, N>>& out, std::string& expected) {
    expected = "a list of node indices, " + std::to_string(N) + " per element";
    auto t = tokens(text);
    if (t.size() % N) return false;
    out.resize(t.size() / N);
    for (size_t i = 0; i < t.size(); ++i)
        if (!parseInt(t[i], out[i / N][i % N]) || out[i / N][i % N] < 0) return false;
    return true;
}

template <class T, size_t N>
std::string formatTuples(const std::vector<std::array<T, N>>& v) {
    std::string s;
    for (auto& a : v)
        for (auto x : a) s += (s.empty() ? "" : " ") + std::to_string(x);
    return s;
}

} // namespace

std::string ParamSpec::rangeText() const {
    if (!choiceList.empty()) {
        std::string s = "one of ";
        for (size_t i = 0; i < choiceList.size(); ++i) s += (i ? "|" : "") + choiceList[i];
        return s;
    }
    if (lo && hi)
        return std::string(loExclusive ? "(" : "[") + formatNumber(*lo, 12) + ", " + formatNumber(*hi, 12) + (hiExclusive ? ")" : "]");
    if (lo) return std::string(loExclusive ? "> " : ">= ") + formatNumber(*lo, 12);
    if (hi) return std::string(hiExclusive ? "< " : "<= ") + formatNumber(*hi, 12);
    return {};
}

// ---- traits -------------------------------------------------------------------------------

const char* ParamTraits<bool>::typeName() { return "bool"; }
bool ParamTraits<bool>::parse(const std::string& t, bool& v, std::string& e) {
    e = "true or false";
    if (t == "true" || t == "1") return v = true, true;
    if (t == "false" || t == "0") return v = false, true;
    return false;
}
std::string ParamTraits<bool>::format(const bool& v) { return v ? "true" : "false"; }
std::string ParamTraits<bool>::check(const bool&, const ParamSpec&) { return {}; }

const char* ParamTraits<int>::typeName() { return "int"; }
bool ParamTraits<int>::parse(const std::string& t, int& v, std::string& e) {
    e = "an integer";
    auto tk = tokens(t);
    return tk.size() == 1 && parseInt(tk[0], v);
}
std::string ParamTraits<int>::format(const int& v) { return std::to_string(v); }
std::string ParamTraits<int>::check(const int& v, const ParamSpec& s) { return checkNumber(v, s); }

const char* ParamTraits<double>::typeName() { return "double"; }
bool ParamTraits<double>::parse(const std::string& t, double& v, std::string& e) {
    e = "a number";
    auto tk = tokens(t);
    return tk.size() == 1 && parseDouble(tk[0], v) && std::isfinite(v);
}
std::string ParamTraits<double>::format(const double& v) { return formatNumber(v, 12); }
std::string ParamTraits<double>::check(const double& v, const ParamSpec& s) { return checkNumber(v, s); }

const char* ParamTraits<std::string>::typeName() { return "string"; }
bool ParamTraits<std::string>::parse(const std::string& t, std::string& v, std::string&) { v = t; return true; }
std::string ParamTraits<std::string>::format(const std::string& v) { return v; }
std::string ParamTraits<std::string>::check(const std::string& v, const ParamSpec& s) {
    if (s.choiceList.empty()) return {};
    for (auto& c : s.choiceList)
        if (c == v) return {};
    return "is not " + s.rangeText();
}

const char* ParamTraits<Vec3>::typeName() { return "vec3"; }
bool ParamTraits<Vec3>::parse(const std::string& t, Vec3& v, std::string& e) {
    e = "three numbers \"x y z\"";
    auto tk = tokens(t);
    if (tk.size() != 3) return false;
    for (int i = 0; i < 3; ++i)
        if (!parseDouble(tk[i], v[i]) || !std::isfinite(v[i])) return false;
    return true;
}
std::string ParamTraits<Vec3>::format(const Vec3& v) {
    return formatNumber(v[0], 12) + " " + formatNumber(v[1], 12) + " " + formatNumber(v[2], 12);
}
std::string ParamTraits<Vec3>::check(const Vec3& v, const ParamSpec& s) {
    return checkEach(std::vector<double>{v[0], v[1], v[2]}, s);
}

const char* ParamTraits<IndexList>::typeName() { return "index list"; }
bool ParamTraits<IndexList>::parse(const std::string& t, IndexList& v, std::string& e) {
    e = "a list of non-negative integers";
    v.clear();
    for (auto& tk : tokens(t)) {
        int i;
        if (!parseInt(tk, i) || i < 0) return false;
        v.push_back(i);
    }
    return true;
}
std::string ParamTraits<IndexList>::format(const IndexList& v) {
    std::string s;
    for (int i : v) s += (s.empty() ? "" : " ") + std::to_string(i);
    return s;
}
std::string ParamTraits<IndexList>::check(const IndexList& v, const ParamSpec& s) {
    auto c = checkCount(v.size(), s);
    return c.empty() ? checkEach(v, s) : c;
}

const char* ParamTraits<NumberList>::typeName() { return "number list"; }
bool ParamTraits<NumberList>::parse(const std::string& t, NumberList& v, std::string& e) {
    e = "a list of numbers";
    v.clear();
    for (auto& tk : tokens(t)) {
        double d;
        if (!parseDouble(tk, d) || !std::isfinite(d)) return false;
        v.push_back(d);
    }
    return true;
}
std::string ParamTraits<NumberList>::format(const NumberList& v) {
    std::string s;
    for (double d : v) s += (s.empty() ? "" : " ") + formatNumber(d, 12);
    return s;
}
std::string ParamTraits<NumberList>::check(const NumberList& v, const ParamSpec& s) {
    auto c = checkCount(v.size(), s);
    return c.empty() ? checkEach(v, s) : c;
}

const char* ParamTraits<FilePath>::typeName() { return "file path"; }
bool ParamTraits<FilePath>::parse(const std::string& t, FilePath& v, std::string& e) {
    e = "a file path";
    if (t.empty()) return false;
    v.written = t;
    v.resolved = t;
    return true;
}
std::string ParamTraits<FilePath>::format(const FilePath& v) { return v.written; }
std::string ParamTraits<FilePath>::check(const FilePath&, const ParamSpec&) { return {}; }

const char* ParamTraits<TimeStep>::typeName() { return "time step"; }
bool ParamTraits<TimeStep>::parse(const std::string& t, TimeStep& v, std::string& e) {
    e = "a positive number of seconds or \"auto\"";
    auto tk = tokens(t);
    if (tk.size() != 1) return false;
    if (tk[0] == "auto") return v = TimeStep{true, 0.0}, true;
    v.automatic = false;
    return parseDouble(tk[0], v.value) && std::isfinite(v.value) && v.value > 0;
}
std::string ParamTraits<TimeStep>::format(const TimeStep& v) {
    return v.automatic ? "auto" : (v.value > 0 ? formatNumber(v.value, 12) : "");
}
std::string ParamTraits<TimeStep>::check(const TimeStep&, const ParamSpec&) { return {}; }

const char* ParamTraits<Positions>::typeName() { return "positions"; }
bool ParamTraits<Positions>::parse(const std::string& t, Positions& v, std::string& e) {
    e = "a list of coordinates, 3 per point";
    auto tk = tokens(t);
    if (tk.size() % 3) return false;
    v.resize(tk.size() / 3);
    for (size_t i = 0; i < tk.size(); ++i)
        if (!parseDouble(tk[i], v[i / 3][i % 3]) || !std::isfinite(v[i / 3][i % 3])) return false;
    return true;
}
std::string ParamTraits<Positions>::format(const Positions& v) {
    std::string s;
    for (auto& p : v) s += (s.empty() ? "" : " ") + ParamTraits<Vec3>::format(p);
    return s;
}
std::string ParamTraits<Positions>::check(const Positions&, const ParamSpec&) { return {}; }

const char* ParamTraits<Tetrahedra>::typeName() { return "tetrahedra"; }
bool ParamTraits<Tetrahedra>::parse(const std::string& t, Tetrahedra& v, std::string& e) { return parseIndexTuples(t, v, e); }
std::string ParamTraits<Tetrahedra>::format(const Tetrahedra& v) { return formatTuples(v); }
std::string ParamTraits<Tetrahedra>::check(const Tetrahedra&, const ParamSpec&) { return {}; }

const char* ParamTraits<Hexahedra>::typeName() { return "hexahedra"; }
bool ParamTraits<Hexahedra>::parse(const std::string& t, Hexahedra& v, std::string& e) { return parseIndexTuples(t, v, e); }
std::string ParamTraits<Hexahedra>::format(const Hexahedra& v) { return formatTuples(v); }
std::string ParamTraits<Hexahedra>::check(const Hexahedra&, const ParamSpec&) { return {}; }

const char* ParamTraits<Triangles>::typeName() { return "triangles"; }
bool ParamTraits<Triangles>::parse(const std::string& t, Triangles& v, std::string& e) { return parseIndexTuples(t, v, e); }
std::string ParamTraits<Triangles>::format(const Triangles& v) { return formatTuples(v); }
std::string ParamTraits<Triangles>::check(const Triangles&, const ParamSpec&) { return {}; }

const char* ParamTraits<MeshData>::typeName() { return "mesh"; }
bool ParamTraits<MeshData>::parse(const std::string&, MeshData&, std::string& e) {
    e = "a link to a mesh (\"@loader.mesh\"): a mesh cannot be written inline";
    return false;
}
std::string ParamTraits<MeshData>::format(const MeshData& m) {
    if (m.points.empty()) return "";
    return std::to_string(m.points.size()) + " points, " + std::to_string(m.tetrahedra.size()) + " tetrahedra, " +
           std::to_string(m.hexahedra.size()) + " hexahedra";
}
std::string ParamTraits<MeshData>::check(const MeshData&, const ParamSpec&) { return {}; }

// ---- BaseParam ----------------------------------------------------------------------------

BaseParam::BaseParam(Base* owner, ParamSpec spec) : m_owner(owner), m_spec(std::move(spec)) {
    if (owner) owner->m_params.push_back(this);
}

void BaseParam::read(const std::string& text, const SourceLoc& loc) {
    m_loc = loc;
    if (m_spec.isOutput && !isComponentLink())
        m_owner->fail(*this, "'" + name() + "' is computed by the component and cannot be set; it can only be linked to");
    if (!text.empty() && text[0] == '@') {
        m_link = text;
        markSet();
        return;
    }
    parseValue(text, loc);
    markSet();
    checkValue();
}

void BaseParam::checkValue() const {
    auto p = rangeProblem();
    if (!p.empty()) m_owner->fail(*this, name() + " = " + valueText().substr(0, 60) + " " + p);
}

void BaseParam::badValue(const std::string& text, const std::string& expected, const SourceLoc& loc) const {
    std::string shown = text.size() > 60 ? text.substr(0, 57) + "..." : text;
    m_owner->fail(*this, name() + " = \"" + shown + "\" is not " + expected);
}

std::string resolveScenePath(const std::string& text, const SourceLoc& loc) {
    namespace fs = std::filesystem;
    fs::path p(text);
    if (p.is_absolute() || loc.file.empty() || loc.file.front() == '<') return p.lexically_normal().string();
    return (fs::path(loc.file).parent_path() / p).lexically_normal().string();
}

} // namespace fascia::core
