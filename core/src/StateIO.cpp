#include "fascia/base/StateIO.h"
#include "fascia/base/Error.h"

#include <cstring>

namespace fascia::core {

namespace {

constexpr char kRecord = 'R', kSection = 'S';

template <class T>
void append(std::string& out, T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(b, sizeof(T));
}

const char* typeName(RecordType t) {
    switch (t) {
    case RecordType::Float64: return "float64";
    case RecordType::Int64: return "int64";
    case RecordType::Bool: return "bool";
    case RecordType::Text: return "text";
    }
    return "unknown";
}

size_t widthOf(RecordType t) {
    switch (t) {
    case RecordType::Float64:
    case RecordType::Int64: return 8;
    default: return 1;
    }
}

} // namespace

std::uint64_t hashBytes(const void* data, size_t size, std::uint64_t seed) {
    // per 8-byte word: h = (h xor w) * odd constant, then a rotation; each step is a bijection of h, so
    // two inputs that differ in one word always hash differently
    const auto* p = static_cast<const unsigned char*>(data);
    std::uint64_t h = seed ^ (size * 0x9e3779b97f4a7c15ULL);
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        std::uint64_t w;
        std::memcpy(&w, p + i, 8);
        h = (h ^ w) * 0x100000001b3ULL;
        h = (h << 23) | (h >> 41);
    }
    std::uint64_t tail = 0;
    for (size_t k = 0; i + k < size; ++k) tail |= std::uint64_t(p[i + k]) << (8 * k);
    h = (h ^ tail) * 0x100000001b3ULL;
    h ^= h >> 31;
    h *= 0xbf58476d1ce4e5b9ULL;
    return h ^ (h >> 29);
}

void StateWriter::putRaw(const std::string& name, RecordType type, const void* data, size_t count, size_t width) {
    if (m_countOnly) {  // the bytes below: marker, name length and name, type, count, values
        m_counted += 1 + 2 + name.size() + 1 + 8 + count * width;
        return;
    }
    m_bytes.push_back(kRecord);
    append<std::uint16_t>(m_bytes, std::uint16_t(name.size()));
    m_bytes += name;
    m_bytes.push_back(char(type));
    append<std::uint64_t>(m_bytes, count);
    if (count) m_bytes.append(static_cast<const char*>(data), count * width);
}

void StateWriter::beginSection(const std::string& path, const std::string& className) {
    if (m_countOnly) {  // marker, path, class, section length (endSection then has nothing to patch)
        m_counted += 1 + 4 + path.size() + 4 + className.size() + 8;
        return;
    }
    m_bytes.push_back(kSection);
    append<std::uint32_t>(m_bytes, std::uint32_t(path.size()));
    m_bytes += path;
    append<std::uint32_t>(m_bytes, std::uint32_t(className.size()));
    m_bytes += className;
    m_sectionLength = m_bytes.size();
    append<std::uint64_t>(m_bytes, 0);
}

void StateWriter::endSection() {
    if (!m_sectionLength) return;
    const std::uint64_t len = m_bytes.size() - (m_sectionLength + 8);
    std::memcpy(&m_bytes[m_sectionLength], &len, 8);
    m_sectionLength = 0;
}

StateReader::StateReader(const std::string& bytes, size_t begin, size_t end, std::string file)
    : m_bytes(bytes), m_pos(begin), m_end(end), m_file(std::move(file)), m_sectionEnd(end) {}

void StateReader::fail(const std::string& message) const { throwInputError({m_file, 0}, message); }

std::string StateReader::where() const { return m_section.empty() ? std::string() : "[" + m_section + "] "; }

void StateReader::need(size_t bytes, const std::string& what) const {
    if (m_sectionEnd - m_pos < bytes || m_pos > m_sectionEnd)
        fail(where() + what + " runs past the end of its section (byte " + std::to_string(m_pos) + ")");
}

void StateReader::beginSection(const std::string& path, const std::string& className) {
    m_section.clear();
    m_sectionEnd = m_end;
    auto text = [&](const char* what) {
        need(4, what);
        std::uint32_t n;
        std::memcpy(&n, &m_bytes[m_pos], 4);
        m_pos += 4;
        need(n, what);
        std::string s = m_bytes.substr(m_pos, n);
        m_pos += n;
        return s;
    };
    if (m_pos >= m_end || m_bytes[m_pos] != kSection)
        fail("no state for " + className + " '" + path + "' (byte " + std::to_string(m_pos) +
             "): the checkpoint was written by a scene with fewer components");
    ++m_pos;
    const std::string p = text("a section name"), c = text("a section name");
    if (p != path || c != className)
        fail("the state at byte " + std::to_string(m_pos) + " is of " + c + " '" + p + "', but this scene has " +
             className + " '" + path + "' there: the checkpoint was written by another scene");
    need(8, "a section length");
    std::uint64_t len;
    std::memcpy(&len, &m_bytes[m_pos], 8);
    m_pos += 8;
    need(len, "the section");
    m_sectionEnd = m_pos + len;
    m_section = path;
}

void StateReader::endSection() {
    if (m_pos != m_sectionEnd) {
        std::string name;
        if (m_bytes[m_pos] == kRecord && m_sectionEnd - m_pos > 3) {
            std::uint16_t n;
            std::memcpy(&n, &m_bytes[m_pos + 1], 2);
            if (size_t(n) + 3 <= m_sectionEnd - m_pos) name = m_bytes.substr(m_pos + 3, n);
        }
        fail(where() + "record '" + name + "' was saved but is not read by this build: the checkpoint was written by "
             "another version of the component");
    }
    m_section.clear();
    m_sectionEnd = m_end;
}

StateReader::Header StateReader::next(const std::string& name, RecordType type) {
    need(1, "record '" + name + "'");
    if (m_bytes[m_pos] != kRecord)
        fail(where() + "record '" + name + "' is missing (the section ends at byte " + std::to_string(m_pos) +
             "): the checkpoint was written by another version of the component");
    Header h;
    ++m_pos;
    need(2, "record '" + name + "'");
    std::uint16_t n;
    std::memcpy(&n, &m_bytes[m_pos], 2);
    m_pos += 2;
    need(size_t(n) + 9, "record '" + name + "'");
    h.name = m_bytes.substr(m_pos, n);
    m_pos += n;
    h.type = RecordType(std::uint8_t(m_bytes[m_pos]));
    ++m_pos;
    std::memcpy(&h.count, &m_bytes[m_pos], 8);
    m_pos += 8;
    if (h.name != name)
        fail(where() + "expected record '" + name + "', found '" + h.name + "': the checkpoint was written by another "
             "version of the component");
    if (h.type != type)
        fail(where() + "record '" + name + "' holds " + typeName(h.type) + " values, " + typeName(type) + " expected");
    const size_t w = widthOf(type);
    if (h.count > (m_sectionEnd - m_pos) / w) need(size_t(-1), "record '" + name + "'");
    h.payload = m_pos;
    m_pos += size_t(h.count) * w;
    return h;
}

double StateReader::getDouble(const std::string& name) {
    double v;
    getInto(name, &v, 1);
    return v;
}

long StateReader::getLong(const std::string& name) {
    const Header h = next(name, RecordType::Int64);
    if (h.count != 1) fail(where() + "record '" + name + "' has " + std::to_string(h.count) + " values, 1 expected");
    std::int64_t v;
    std::memcpy(&v, &m_bytes[h.payload], 8);
    return long(v);
}

bool StateReader::getBool(const std::string& name) {
    const Header h = next(name, RecordType::Bool);
    if (h.count != 1) fail(where() + "record '" + name + "' has " + std::to_string(h.count) + " values, 1 expected");
    return m_bytes[h.payload] != 0;
}

std::string StateReader::getText(const std::string& name) {
    const Header h = next(name, RecordType::Text);
    return m_bytes.substr(h.payload, size_t(h.count));
}

void StateReader::getInto(const std::string& name, double* v, size_t n) {
    const Header h = next(name, RecordType::Float64);
    if (h.count != n)
        fail(where() + "record '" + name + "' has " + std::to_string(h.count) + " values, this scene needs " +
             std::to_string(n));
    if (n) std::memcpy(v, &m_bytes[h.payload], 8 * n);
}

std::vector<double> StateReader::getDoubles(const std::string& name) {
    const Header h = next(name, RecordType::Float64);
    std::vector<double> v(size_t(h.count));
    if (!v.empty()) std::memcpy(v.data(), &m_bytes[h.payload], 8 * v.size());
    return v;
}

} // namespace fascia::core
