#include "fascia/sim/LoadCurve.h"
#include "fascia/base/Format.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace fascia::core {

namespace {

/// s(r) = r^3 (10 - 15 r + 6 r^2) and its derivative 30 r^2 (1 - r)^2.
double smooth(double r) { return r * r * r * (10 - 15 * r + 6 * r * r); }
double smoothRate(double r) { return 30 * r * r * (1 - r) * (1 - r); }

} // namespace

std::string Curve::make(const std::vector<double>& points, Interpolation interp, After after, Curve& out) {
    if (points.empty()) return "has no points: give times and values, \"t1 c1 t2 c2 ...\"";
    if (points.size() % 2)
        return "has " + std::to_string(points.size()) + " numbers, an odd count: give pairs of a time and a value";
    for (double p : points)
        if (!std::isfinite(p)) return "holds a non-finite number";
    Curve c;
    c.m_t.clear();
    c.m_c.clear();
    for (size_t k = 0; k < points.size(); k += 2) {
        if (k && points[k] < points[k - 2])
            return "times must not decrease: point " + std::to_string(k / 2 + 1) + " is at t = " + formatNumber(points[k], 12) +
                   " s, after t = " + formatNumber(points[k - 2], 12) + " s";
        c.m_t.push_back(points[k]);
        c.m_c.push_back(points[k + 1]);
    }
    if (after == After::Extend && interp == Interpolation::Smooth)
        return "extend continues a linear segment: it needs linear interpolation";
    if (after == After::Extend && c.m_t.size() < 2) return "extend needs at least two points";
    if (after == After::Extend && c.m_t[c.m_t.size() - 1] == c.m_t[c.m_t.size() - 2])
        return "extend continues the last segment, which is a jump here";
    c.m_interp = interp;
    c.m_after = after;
    out = std::move(c);
    return {};
}

std::string Curve::parse(const std::string& text, Curve& out) {
    std::istringstream is(text);
    std::vector<std::string> words;
    for (std::string w; is >> w;) words.push_back(w);
    const std::string forms = "write \"ramp T\", \"smoothStep T\", \"step t0\", \"linear t1 c1 t2 c2 ...\" or "
                              "\"smooth t1 c1 ...\" (optionally ending in \"extend\"), or link a LoadCurve: \"@name\"";
    if (words.empty()) return "is empty: " + forms;
    After after = After::Hold;
    if (words.size() > 1 && words.back() == "extend") {
        after = After::Extend;
        words.pop_back();
    }
    std::vector<double> nums;
    for (size_t i = 1; i < words.size(); ++i) {
        char* end = nullptr;
        const double v = std::strtod(words[i].c_str(), &end);
        if (end != words[i].c_str() + words[i].size() || !std::isfinite(v))
            return "'" + words[i] + "' is not a number: " + forms;
        nums.push_back(v);
    }
    const std::string& kind = words[0];
    auto one = [&](const char* what) -> std::string {
        return nums.size() == 1 ? std::string() : "\"" + kind + "\" takes one number, " + what;
    };
    if (kind == "ramp" || kind == "smoothStep") {
        if (auto e = one("the duration T in seconds"); !e.empty()) return e;
        if (!(nums[0] > 0)) return "\"" + kind + "\" needs a duration T > 0, not " + formatNumber(nums[0], 12);
        return make({0.0, 0.0, nums[0], 1.0}, kind == "ramp" ? Interpolation::Linear : Interpolation::Smooth, after, out);
    }
    if (kind == "step") {
        if (auto e = one("the time t0 of the step"); !e.empty()) return e;
        return make({nums[0], 0.0, nums[0], 1.0}, Interpolation::Linear, after, out);
    }
    if (kind == "linear" || kind == "smooth")
        return make(nums, kind == "linear" ? Interpolation::Linear : Interpolation::Smooth, after, out);
    return "'" + kind + "' is no curve form: " + forms;
}

double Curve::value(double t) const {
    const size_t n = m_t.size();
    if (!(t > m_t[0])) return m_c[0];
    if (t > m_t[n - 1]) {
        if (m_after == After::Hold) return m_c[n - 1];
        const double slope = (m_c[n - 1] - m_c[n - 2]) / (m_t[n - 1] - m_t[n - 2]);
        return m_c[n - 1] + slope * (t - m_t[n - 1]);
    }
    // the segment (t_(k-1), t_k] holding t: a jump's time takes its first value
    const size_t k = size_t(std::lower_bound(m_t.begin(), m_t.end(), t) - m_t.begin());
    const double r = (t - m_t[k - 1]) / (m_t[k] - m_t[k - 1]);
    const double w = m_interp == Interpolation::Linear ? r : smooth(r);
    return m_c[k - 1] + (m_c[k] - m_c[k - 1]) * w;
}

double Curve::rate(double t) const {
    const size_t n = m_t.size();
    if (!(t > m_t[0])) return 0.0;
    if (!(t < m_t[n - 1])) {
        if (m_after == After::Hold) return 0.0;
        return (m_c[n - 1] - m_c[n - 2]) / (m_t[n - 1] - m_t[n - 2]);
    }
    // the segment [t_(k-1), t_k) holding t: the derivative from the right
    const size_t k = size_t(std::upper_bound(m_t.begin(), m_t.end(), t) - m_t.begin());
    const double h = m_t[k] - m_t[k - 1], r = (t - m_t[k - 1]) / h;
    const double w = m_interp == Interpolation::Linear ? 1.0 : smoothRate(r);
    return (m_c[k] - m_c[k - 1]) * w / h;
}

std::string Curve::text() const {
    std::string s = m_interp == Interpolation::Linear ? "linear" : "smooth";
    for (size_t k = 0; k < m_t.size(); ++k) s += " " + formatNumber(m_t[k], 12) + " " + formatNumber(m_c[k], 12);
    if (m_after == After::Extend) s += " extend";
    return s;
}

void CurveParam::parseValue(const std::string& text, const SourceLoc&) {
    Curve c;
    const std::string problem = Curve::parse(text, c);
    if (!problem.empty()) m_owner->fail(*this, name() + " = \"" + text + "\" " + problem);
    m_inline = c;
    m_text = text;
    m_target = nullptr;
}

ParamSpec curveSpec(const char* name, const std::string& what) {
    return ParamSpec(name).help(
        "load curve c(t) scaling " + what +
        ": a link to a LoadCurve (\"@ramp\") or inline: \"ramp T\" (0 to 1 linearly over T s, then held), "
        "\"smoothStep T\" (the same, smooth 3-4-5 polynomial), \"step t0\" (0, then 1 after t0), \"linear t1 c1 t2 c2 "
        "...\" or \"smooth t1 c1 ...\" (tabulated, last value held), any ending in \"extend\" to continue the last "
        "segment instead (default: 1 at all times)");
}

} // namespace fascia::core
