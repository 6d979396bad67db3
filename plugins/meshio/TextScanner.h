#pragma once
/// The shared text scanner of the line-based mesh formats (Gmsh, TetGen): records are one per line,
/// and a record that ends early, has extra values or holds a malformed number is an error located
/// at its own line ("file:line: error: ..."). Private to the readers.
#include "ReaderSupport.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

namespace fascia::meshio::detail {

inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Walks a text one token at a time and counts its lines; the comment character (if any) starts a
/// comment that runs to the end of the line.
class TextScanner {
public:
    TextScanner(std::string_view text, const std::string& file, char comment = '\0')
        : m_p(text.data()), m_end(text.data() + text.size()), m_file(file), m_comment(comment) {}

    const std::string& file() const { return m_file; }
    int line() const { return m_line; }
    /// Line of the last token read (for "the file ends after line N").
    int lastLine() const { return m_lastTokenLine; }
    /// Describes the records of the current section for "ends early" messages, e.g. "'id x y z'".
    void setRecordFormat(std::string fmt) { m_format = std::move(fmt); }

    /// Moves to the first token of the next line that has one; false at the end of the file.
    bool nextRecord() {
        for (;;) {
            while (m_p < m_end && isBlank(*m_p)) ++m_p;
            if (m_p == m_end) return false;
            if (*m_p == '\n') {
                ++m_line;
                ++m_p;
                continue;
            }
            if (m_comment && *m_p == m_comment) {
                skipRestOfLine();
                continue;
            }
            return true;
        }
    }
    /// Bytes left after the current position: a bound for any count the file announces.
    long long remaining() const { return (long long)(m_end - m_p); }
    /// First character of the record nextRecord() moved to.
    char peek() const { return m_p < m_end ? *m_p : '\0'; }

    /// Next token on the current line; empty at the end of the line.
    std::string_view token() {
        while (m_p < m_end && isBlank(*m_p)) ++m_p;
        if (m_p == m_end || *m_p == '\n' || (m_comment && *m_p == m_comment)) return {};
        const char* s = m_p;
        while (m_p < m_end && !isBlank(*m_p) && *m_p != '\n' && !(m_comment && *m_p == m_comment)) ++m_p;
        m_lastTokenLine = m_line;
        return {s, size_t(m_p - s)};
    }
    bool lineHasMore() {
        while (m_p < m_end && isBlank(*m_p)) ++m_p;
        return !(m_p == m_end || *m_p == '\n' || (m_comment && *m_p == m_comment));
    }
    /// The rest of the current line, trimmed.
    std::string_view restOfLine() {
        while (m_p < m_end && isBlank(*m_p)) ++m_p;
        const char* s = m_p;
        while (m_p < m_end && *m_p != '\n') ++m_p;
        const char* e = m_p;
        while (e > s && isBlank(e[-1])) --e;
        if (e > s) m_lastTokenLine = m_line;
        return {s, size_t(e - s)};
    }
    void skipRestOfLine() {
        const void* nl = std::memchr(m_p, '\n', size_t(m_end - m_p));
        m_p = nl ? static_cast<const char*>(nl) : m_end;
    }
    void expectEndOfLine(const std::string& after) {
        const std::string_view t = token();
        if (!t.empty())
            fail(m_file, m_line, "unexpected " + quoted(t) + " after " + after + ": the line has more values than expected" +
                                     formatHint());
    }

    /// A required token of the current record.
    std::string_view field(const char* what) {
        const std::string_view t = token();
        if (t.empty()) fail(m_file, m_line, std::string("the line ends before the ") + what + formatHint());
        return t;
    }
    long long integer(const char* what) { return toInteger(field(what), what); }
    int smallInteger(const char* what) {
        const long long v = integer(what);
        if (v < -2147483647LL || v > 2147483647LL)
            fail(m_file, m_line, std::string("the ") + what + " " + std::to_string(v) + " is out of range");
        return int(v);
    }
    double real(const char* what) { return toReal(field(what), what); }

    long long toInteger(std::string_view t, const char* what) const {
        const char* b = t.data();
        const char* e = b + t.size();
        if (b < e && *b == '+' && e - b > 1 && b[1] != '-') ++b;
        long long v = 0;
        const auto [ptr, ec] = std::from_chars(b, e, v);
        if (ec == std::errc::result_out_of_range)
            fail(m_file, m_line, std::string("the ") + what + " " + quoted(t) + " is out of range");
        if (ec != std::errc() || ptr != e)
            fail(m_file, m_line, std::string("malformed number ") + quoted(t) + " for the " + what +
                                     ": expected a whole number" + formatHint());
        return v;
    }
    double toReal(std::string_view t, const char* what) const {
        const char* b = t.data();
        const char* e = b + t.size();
        if (b < e && *b == '+' && e - b > 1 && b[1] != '-') ++b;
        double v = 0;
        const auto [ptr, ec] = std::from_chars(b, e, v, std::chars_format::general);
        if (ec == std::errc::result_out_of_range) {
            // underflow to a denormal/zero is harmless; overflow is not
            const double big = std::strtod(std::string(t).c_str(), nullptr);
            if (std::isinf(big))
                fail(m_file, m_line, std::string("the ") + what + " " + quoted(t) + " is out of range");
            return big;
        }
        if (ec != std::errc() || ptr != e)
            fail(m_file, m_line, std::string("malformed number ") + quoted(t) + " for the " + what +
                                     ": expected a decimal number such as 0.25 or -1.5e-3" + formatHint());
        return v;
    }

private:
    std::string formatHint() const { return m_format.empty() ? std::string() : " (records here are " + m_format + ")"; }

    const char* m_p;
    const char* m_end;
    const std::string& m_file;
    char m_comment;
    int m_line = 1;
    int m_lastTokenLine = 1;
    std::string m_format;
};

} // namespace fascia::meshio::detail
