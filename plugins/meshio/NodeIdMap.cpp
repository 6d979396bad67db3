#include "NodeIdMap.h"
#include "ReaderSupport.h"

#include <algorithm>

namespace fascia::meshio::detail {

namespace {

[[noreturn]] void duplicate(long long id, int firstLine, int line, const std::string& file) {
    fail(file, line, "node id " + std::to_string(id) + " appears twice (first on line " + std::to_string(firstLine) +
                         "): node ids must be unique");
}

} // namespace

void NodeIdMap::build(const std::vector<long long>& ids, const std::vector<int>& lines, const std::string& file) {
    m_dense = true;
    m_table.clear();
    m_hash.clear();
    if (ids.empty()) return;
    const long long lo = *std::min_element(ids.begin(), ids.end());
    const long long hi = *std::max_element(ids.begin(), ids.end());
    m_dense = lo >= 0 && hi < 4 * (long long)ids.size() + 1024;
    if (m_dense) {
        m_table.assign(size_t(hi) + 1, -1);
        for (size_t i = 0; i < ids.size(); ++i) {
            int& slot = m_table[size_t(ids[i])];
            if (slot >= 0) duplicate(ids[i], lines[size_t(slot)], lines[i], file);
            slot = int(i);
        }
    } else {
        m_hash.reserve(ids.size() * 2);
        for (size_t i = 0; i < ids.size(); ++i) {
            const auto [it, inserted] = m_hash.emplace(ids[i], int(i));
            if (!inserted) duplicate(ids[i], lines[size_t(it->second)], lines[i], file);
        }
    }
}

} // namespace fascia::meshio::detail
