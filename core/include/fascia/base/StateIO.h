#pragma once
/// What a component carries from one step to the next, as typed, named and sized records: the
/// checkpoint file (Simulation::save / restore) and the in-memory snapshot of the divergence check
/// are sequences of them. A component writes its records in saveState() and reads them back, in the
/// same order, in restoreState(); the reader checks each record's name, type and size against what
/// the component asks for, so that a mismatch is an error naming the record, never garbage read.
#include "fascia/base/Types.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fascia::core {

/// The type of a record's values.
enum class RecordType : std::uint8_t { Float64 = 1, Int64 = 2, Bool = 3, Text = 4 };

/// A 64-bit hash of bytes (8 at a time: any change of one 8-byte word changes it), seeded so that
/// hashes can be chained: hashBytes(b, nb, hashBytes(a, na)).
std::uint64_t hashBytes(const void* data, size_t size, std::uint64_t seed = 0x5a17c0de2f3e9b41ULL);

/// Appends records to a byte buffer (host byte order: a checkpoint is for the machine kind that
/// wrote it; Simulation::save records the byte order and restore checks it).
class StateWriter {
public:
    StateWriter() = default;
    /// A writer that only counts: size() is the bytes the records would take, bytes() stays empty
    /// (to reserve a buffer at its final size before writing, instead of growing it record by record).
    struct CountOnly {};
    explicit StateWriter(CountOnly) : m_countOnly(true) {}
    /// Bytes written (counted, for a counting writer).
    size_t size() const { return m_countOnly ? m_counted : m_bytes.size(); }
    void put(const std::string& name, double v) { putRaw(name, RecordType::Float64, &v, 1, sizeof v); }
    void put(const std::string& name, long v) {
        const std::int64_t w = v;
        putRaw(name, RecordType::Int64, &w, 1, sizeof w);
    }
    void put(const std::string& name, int v) { put(name, long(v)); }
    void put(const std::string& name, bool v) {
        const std::uint8_t b = v ? 1 : 0;
        putRaw(name, RecordType::Bool, &b, 1, 1);
    }
    void put(const std::string& name, const std::string& v) { putRaw(name, RecordType::Text, v.data(), v.size(), 1); }
    void put(const std::string& name, const char* v) { put(name, std::string(v)); }
    /// n doubles.
    void put(const std::string& name, const double* v, size_t n) { putRaw(name, RecordType::Float64, v, n, sizeof(double)); }
    void put(const std::string& name, const std::vector<double>& v) { put(name, v.data(), v.size()); }
    /// 3 doubles per point.
    void put(const std::string& name, const Positions& p) { put(name, p.empty() ? nullptr : p.data()->data(), 3 * p.size()); }

    /// Starts a section (one component's records): its path and class, checked on reading.
    void beginSection(const std::string& path, const std::string& className);
    /// Ends it (records its length, so that a reader can tell what it did not read).
    void endSection();
    const std::string& bytes() const { return m_bytes; }
    std::string& bytes() { return m_bytes; }
    void clear() {
        m_bytes.clear();
        m_counted = 0;
    }

private:
    void putRaw(const std::string& name, RecordType type, const void* data, size_t count, size_t width);
    std::string m_bytes;
    size_t m_sectionLength = 0;  ///< where the open section's length goes (0: none open)
    bool m_countOnly = false;
    size_t m_counted = 0;  ///< counting writer: the bytes so far
};

/// Reads the records a StateWriter wrote. Every failure throws an input error (exit 2) located at
/// the file it came from, naming the section (component) and the record.
class StateReader {
public:
    /// Reads bytes [begin, end) of `bytes`; `file` names them in messages.
    StateReader(const std::string& bytes, size_t begin, size_t end, std::string file);

    double getDouble(const std::string& name);
    long getLong(const std::string& name);
    bool getBool(const std::string& name);
    std::string getText(const std::string& name);
    /// Exactly n doubles into v (an error when the record holds another number of values).
    void getInto(const std::string& name, double* v, size_t n);
    /// A record of any length.
    std::vector<double> getDoubles(const std::string& name);
    /// Exactly p.size() points (the size the scene gives it).
    void getInto(const std::string& name, Positions& p) { getInto(name, p.empty() ? nullptr : p.data()->data(), 3 * p.size()); }

    /// Opens the next section, which must be the one of `path` and `className`.
    void beginSection(const std::string& path, const std::string& className);
    /// Closes it: an error when a record of it was not read (the component saved more than it reads).
    void endSection();
    /// True when every byte was read.
    bool atEnd() const { return m_pos == m_end; }
    /// A located input error about the file: "file: error: message".
    [[noreturn]] void fail(const std::string& message) const;

private:
    struct Header {
        std::string name;
        RecordType type;
        std::uint64_t count;
        size_t payload;  ///< where its values start
    };
    /// The next record, which must be called `name` and hold values of `type`.
    Header next(const std::string& name, RecordType type);
    void need(size_t bytes, const std::string& what) const;
    std::string where() const;
    const std::string& m_bytes;
    size_t m_pos, m_end;
    std::string m_file, m_section;
    size_t m_sectionEnd = 0;
};

} // namespace fascia::core
