#pragma once
/// The token and array scanner of the legacy VTK reader (LegacyVTKReader.cpp): keywords and counts
/// are text, the arrays are text (ASCII files) or big-endian binary (BINARY files). Every count is
/// checked against the bytes left in the file before anything is allocated, and every error is
/// located: "file:N: error: ..." at the line of an ASCII file, "file: byte N: error: ..." at the byte
/// offset of a BINARY file. Private to the readers.
#include "ReaderSupport.h"

#include <cctype>
#include <charconv>
#include <cstdlib>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace fascia::meshio::detail {

/// A data type of the legacy format ("float", "vtktypeint64", ...).
struct VtkDataType {
    std::string name;   ///< as in the file, lower case
    int bytes = 0;      ///< size of one value in a BINARY file
    bool real = false;  ///< float or double
    bool isSigned = true;
};

/// Parses a legacy data type name (case-insensitive); false for names the reader does not support
/// ("bit", "string", unknown names).
inline bool parseVtkDataType(std::string_view word, VtkDataType& t) {
    std::string n(word);
    for (auto& c : n) c = char(std::tolower((unsigned char)c));
    struct Known {
        const char* name;
        int bytes;
        bool real, isSigned;
    };
    static const Known known[] = {
        {"unsigned_char", 1, false, false}, {"char", 1, false, true},          {"signed_char", 1, false, true},
        {"unsigned_short", 2, false, false}, {"short", 2, false, true},        {"unsigned_int", 4, false, false},
        {"int", 4, false, true},             {"unsigned_long", 8, false, false}, {"long", 8, false, true},
        {"unsigned_long_long", 8, false, false}, {"long_long", 8, false, true}, {"vtkidtype", 8, false, true},
        {"vtktypeint8", 1, false, true},     {"vtktypeuint8", 1, false, false}, {"vtktypeint16", 2, false, true},
        {"vtktypeuint16", 2, false, false},  {"vtktypeint32", 4, false, true},  {"vtktypeuint32", 4, false, false},
        {"vtktypeint64", 8, false, true},    {"vtktypeuint64", 8, false, false}, {"float", 4, true, true},
        {"double", 8, true, true},           {"vtktypefloat32", 4, true, true}, {"vtktypefloat64", 8, true, true},
    };
    for (const auto& k : known)
        if (n == k.name) {
            t = {n, k.bytes, k.real, k.isSigned};
            return true;
        }
    return false;
}

class LegacyVtkScanner {
public:
    LegacyVtkScanner(std::string_view text, const std::string& file)
        : m_begin(text.data()), m_p(text.data()), m_end(text.data() + text.size()), m_file(file) {
        if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) m_p += 3;  // a UTF-8 byte-order mark
    }

    void setBinary(bool binary) { m_binary = binary; }
    bool binary() const { return m_binary; }
    bool atEnd() {
        skipSpace();
        return m_p == m_end;
    }
    /// Where the last token (or value) was: its line in an ASCII file, its byte offset in a binary one.
    long long where() const { return m_binary ? m_tokOffset : m_tokLine; }

    /// An input error at `where` (a line of an ASCII file, a byte offset of a binary one).
    [[noreturn]] void failAt(long long at, const std::string& message) const {
        if (m_binary) failAtByte(m_file, at, message);
        fail(m_file, int(at), message);
    }
    [[noreturn]] void failHere(const std::string& message) const { failAt(where(), message); }

    /// One header line (the first three of the file), without its line end; false at the end.
    bool headerLine(std::string_view& line) {
        if (m_p == m_end) return false;
        m_tokLine = m_line;
        m_tokOffset = m_p - m_begin;
        const char* s = m_p;
        while (m_p < m_end && *m_p != '\n') ++m_p;
        const char* e = m_p;
        if (m_p < m_end) {
            ++m_p;
            ++m_line;
        }
        while (e > s && (e[-1] == '\r' || e[-1] == ' ' || e[-1] == '\t')) --e;
        line = {s, size_t(e - s)};
        return true;
    }

    /// The next word (skipping white space and line ends); empty at the end of the file.
    std::string_view word() {
        skipSpace();
        return take();
    }
    /// The next word of the current line; empty when the line has no more.
    std::string_view wordOnLine() {
        while (m_p < m_end && (*m_p == ' ' || *m_p == '\t' || *m_p == '\r')) ++m_p;
        if (m_p == m_end || *m_p == '\n') return {};
        return take();
    }
    /// A required word, lower case, for keywords.
    std::string keyword(const char* what) {
        const std::string_view w = word();
        if (w.empty()) failHere(std::string("the file ends before the ") + what + ": the file is truncated");
        return lower(w);
    }
    /// A count on the current line (a whole number >= 0).
    long long count(const char* what) {
        const std::string_view w = wordOnLine();
        if (w.empty()) failHere(std::string("the line ends before the ") + what);
        long long v = 0;
        const auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
        if (ec != std::errc() || ptr != w.data() + w.size() || v < 0)
            failHere("the " + std::string(what) + " " + quoted(w) + " is not a whole number >= 0");
        return v;
    }
    /// Skips the rest of the current line (comments of a header, the line end before binary data).
    void endLine() {
        while (m_p < m_end && *m_p != '\n') ++m_p;
        if (m_p < m_end) {
            ++m_p;
            ++m_line;
        }
    }
    /// Skips lines up to and including the next empty one (a METADATA block).
    void skipToEmptyLine() {
        endLine();
        while (m_p < m_end) {
            const char* s = m_p;
            endLine();
            bool empty = true;
            for (const char* c = s; c < m_p; ++c)
                if (!(*c == ' ' || *c == '\t' || *c == '\r' || *c == '\n')) empty = false;
            if (empty) return;
        }
    }

    /// Fails unless n values (n = tuples * components) of type t fit in what is left of the file: a
    /// binary value takes t.bytes bytes, an ASCII one at least 2 (a digit and a separator).
    void requireRoom(long long tuples, long long components, const VtkDataType& t, const std::string& what) const {
        const unsigned long long left = (unsigned long long)(m_end - m_p);
        const unsigned long long room = m_binary ? left / unsigned(t.bytes) : (left + 1) / 2;
        if (components < 0 || tuples < 0 || (components != 0 && (unsigned long long)tuples > room / (unsigned long long)components))
            failHere(what + ": the file announces " + std::to_string(tuples) + " x " + std::to_string(components) +
                     " values, more than the " + std::to_string(left) + " bytes left in the file can hold (" +
                     (m_binary ? std::to_string(t.bytes) + " bytes per " + t.name + " value" : "an ASCII value takes 2 bytes or more") +
                     "): the count is wrong or the file is truncated");
    }

    /// n values of type t as doubles (checked with requireRoom first); a float array is rounded to
    /// float as VTK stores it. lines, when given, gets where() of every value i with i % stride == 0.
    std::vector<double> reals(long long n, const VtkDataType& t, const std::string& what, int stride = 1,
                              std::vector<long long>* wheres = nullptr) {
        requireRoom(n, 1, t, what);
        beginData();
        std::vector<double> out(static_cast<size_t>(n));
        if (wheres) wheres->reserve(size_t(n / stride));
        for (long long i = 0; i < n; ++i) {
            out[size_t(i)] = m_binary ? binaryValue(t) : asciiValue(t, what, i, n);
            if (wheres && i % stride == 0) wheres->push_back(where());
        }
        return out;
    }
    /// n whole numbers of type t (an integer type); wheres as in reals().
    std::vector<long long> integers(long long n, const VtkDataType& t, const std::string& what,
                                    std::vector<long long>* wheres = nullptr) {
        if (t.real) failHere(what + " must have an integer type, not " + t.name);
        requireRoom(n, 1, t, what);
        beginData();
        std::vector<long long> out(static_cast<size_t>(n));
        if (wheres) wheres->reserve(size_t(n));
        for (long long i = 0; i < n; ++i) {
            out[size_t(i)] = m_binary ? binaryInteger(t) : asciiInteger(what, i, n);
            if (wheres) wheres->push_back(where());
        }
        return out;
    }

    static std::string lower(std::string_view w) {
        std::string s(w);
        for (auto& c : s) c = char(std::tolower((unsigned char)c));
        return s;
    }

private:
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }
    void skipSpace() {
        while (m_p < m_end && isSpace(*m_p)) {
            if (*m_p == '\n') ++m_line;
            ++m_p;
        }
    }
    std::string_view take() {
        m_tokLine = m_line;
        m_tokOffset = m_p - m_begin;
        const char* s = m_p;
        while (m_p < m_end && !isSpace(*m_p)) ++m_p;
        return {s, size_t(m_p - s)};
    }
    /// Binary data starts after the line end of its keyword line.
    void beginData() {
        if (m_binary) endLine();
    }
    std::uint64_t bigEndian(int bytes, const std::string& what) {
        m_tokOffset = m_p - m_begin;
        if (m_end - m_p < bytes) failHere(what + ": the file ends inside the binary data");  // requireRoom makes this rare
        std::uint64_t v = 0;
        for (int k = 0; k < bytes; ++k) v = (v << 8) | (unsigned char)m_p[k];
        m_p += bytes;
        return v;
    }
    double binaryValue(const VtkDataType& t) {
        const std::uint64_t raw = bigEndian(t.bytes, t.name + " data");
        if (t.real) {
            if (t.bytes == 4) {
                const auto u = std::uint32_t(raw);
                float f;
                std::memcpy(&f, &u, 4);
                return f;
            }
            double d;
            std::memcpy(&d, &raw, 8);
            return d;
        }
        return double(signExtend(raw, t));
    }
    long long binaryInteger(const VtkDataType& t) { return signExtend(bigEndian(t.bytes, t.name + " data"), t); }
    long long signExtend(std::uint64_t raw, const VtkDataType& t) const {
        if (!t.isSigned) {
            if (raw > std::uint64_t(INT64_MAX)) failHere("the " + t.name + " value " + std::to_string(raw) + " is out of range");
            return (long long)raw;
        }
        const int shift = 64 - 8 * t.bytes;
        return (long long)(raw << shift) >> shift;
    }
    std::string_view valueWord(const std::string& what, long long i, long long n) {
        const std::string_view w = word();
        if (w.empty())
            failHere("the file ends after " + std::to_string(i) + " of the " + std::to_string(n) + " values of " + what +
                     ": the file is truncated or the count is wrong");
        return w;
    }
    double asciiValue(const VtkDataType& t, const std::string& what, long long i, long long n) {
        const std::string_view w = valueWord(what, i, n);
        if (!t.real) return double(parseInteger(w, what));
        const char* b = w.data();
        const char* e = b + w.size();
        if (b < e && *b == '+') ++b;
        if (t.bytes == 4) {
            float f = 0;
            const auto [ptr, ec] = std::from_chars(b, e, f, std::chars_format::general);
            if (ec == std::errc::result_out_of_range) return double(std::strtof(std::string(w).c_str(), nullptr));
            if (ec != std::errc() || ptr != e) malformed(w, what);
            return f;
        }
        double d = 0;
        const auto [ptr, ec] = std::from_chars(b, e, d, std::chars_format::general);
        if (ec == std::errc::result_out_of_range) return std::strtod(std::string(w).c_str(), nullptr);
        if (ec != std::errc() || ptr != e) malformed(w, what);
        return d;
    }
    long long asciiInteger(const std::string& what, long long i, long long n) { return parseInteger(valueWord(what, i, n), what); }
    long long parseInteger(std::string_view w, const std::string& what) const {
        const char* b = w.data();
        const char* e = b + w.size();
        if (b < e && *b == '+') ++b;
        long long v = 0;
        const auto [ptr, ec] = std::from_chars(b, e, v);
        if (ec == std::errc::result_out_of_range) failHere("the value " + quoted(w) + " of " + what + " is out of range");
        if (ec != std::errc() || ptr != e) failHere("malformed number " + quoted(w) + " in " + what + ": expected a whole number");
        return v;
    }
    [[noreturn]] void malformed(std::string_view w, const std::string& what) const {
        failHere("malformed number " + quoted(w) + " in " + what + ": expected a decimal number such as 0.25 or -1.5e-3");
    }

    const char* m_begin;
    const char* m_p;
    const char* m_end;
    const std::string& m_file;
    bool m_binary = false;
    int m_line = 1;
    int m_tokLine = 1;
    long long m_tokOffset = 0;
};

} // namespace fascia::meshio::detail
