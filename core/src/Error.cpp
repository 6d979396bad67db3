#include "fascia/base/Error.h"

#include <algorithm>
#include <cctype>

namespace fascia::core {

std::string SourceLoc::str() const {
    if (file.empty()) return {};
    if (byte >= 0) return file + ": byte " + std::to_string(byte);
    return line > 0 ? file + ":" + std::to_string(line) : file;
}

std::string Error::format(const SourceLoc& loc, const std::string& message,
                          const std::vector<std::string>& notes) {
    const std::string prefix = loc.empty() ? std::string() : loc.str() + ": ";
    std::string out = prefix + "error: " + message;
    for (const auto& n : notes) out += "\n" + prefix + "note: " + n;
    return out;
}

Error::Error(ErrorKind kind, SourceLoc loc, std::string message, std::vector<std::string> notes)
    : std::runtime_error(format(loc, message, notes)), m_kind(kind), m_loc(std::move(loc)),
      m_message(std::move(message)), m_notes(std::move(notes)) {}

namespace {
/// The text of an error standing for several: each one's own text, one after the other, then the
/// count of those not shown.
std::string joined(const Error& first, const std::vector<Error>& more, size_t unshown, const SourceLoc& where) {
    std::string out = first.what();
    for (const Error& e : more) out += std::string("\n") + e.what();
    if (unshown > 0)
        out += "\n" + (where.empty() ? std::string() : where.str() + ": ") + "note: " + std::to_string(unshown) + " more " +
               (unshown == 1 ? "error" : "errors") + " not shown";
    return out;
}
} // namespace

Error::Error(const Error& first, std::vector<Error> more, size_t unshown, const SourceLoc& where)
    : std::runtime_error(joined(first, more, unshown, where)), m_kind(first.m_kind), m_loc(first.m_loc),
      m_message(first.m_message), m_notes(first.m_notes),
      m_more(more.empty() ? nullptr : std::make_shared<const std::vector<Error>>(std::move(more))), m_unshown(unshown) {}

const std::vector<Error>& Error::more() const {
    static const std::vector<Error> none;
    return m_more ? *m_more : none;
}

void throwInputError(const SourceLoc& loc, const std::string& message, std::vector<std::string> notes) {
    throw Error(ErrorKind::Input, loc, message, std::move(notes));
}

void throwOutputError(const SourceLoc& loc, const std::string& message, std::vector<std::string> notes) {
    throw Error(ErrorKind::Output, loc, message, std::move(notes));
}

void throwSimulationError(const std::string& message) {
    throw Error(ErrorKind::Simulation, {}, message);
}

int editDistance(const std::string& a, const std::string& b) {
    std::vector<int> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) prev[j] = int(j);
    for (size_t i = 1; i <= a.size(); ++i) {
        cur[0] = int(i);
        for (size_t j = 1; j <= b.size(); ++j) {
            const int sub = std::tolower((unsigned char)a[i - 1]) == std::tolower((unsigned char)b[j - 1]) ? 0 : 1;
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + sub});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

std::vector<std::string> closestMatches(const std::string& word, const std::vector<std::string>& candidates,
                                        size_t max) {
    auto lower = [](std::string s) {
        for (auto& c : s) c = char(std::tolower((unsigned char)c));
        return s;
    };
    const std::string lw = lower(word);
    std::vector<std::pair<int, std::string>> scored;
    for (const auto& c : candidates) {
        const std::string lc = lower(c);
        int d = editDistance(word, c);
        // a prefix or substring match counts as close too ("Mesh" -> "MeshLoader")
        if (!lw.empty() && (lc.find(lw) != std::string::npos || lw.find(lc) != std::string::npos))
            d = std::min(d, 1 + int(std::abs(int(lc.size()) - int(lw.size()))) / 4);
        const int limit = std::max(2, int(std::max(word.size(), c.size())) / 3);
        if (d <= limit) scored.emplace_back(d, c);
    }
    std::stable_sort(scored.begin(), scored.end(), [](auto& x, auto& y) { return x.first < y.first; });
    std::vector<std::string> out;
    for (size_t i = 0; i < scored.size() && i < max; ++i) out.push_back(scored[i].second);
    return out;
}

} // namespace fascia::core
