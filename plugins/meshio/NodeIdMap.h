#pragma once
/// File node ids -> 0-based node indices, for meshes whose ids may start anywhere or have gaps.
/// Private to the readers.
#include <string>
#include <unordered_map>
#include <vector>

namespace fascia::meshio::detail {

class NodeIdMap {
public:
    /// ids[i] is the file's id of node i, lines[i] the line it is on. A repeated id is an error
    /// located at its second line.
    void build(const std::vector<long long>& ids, const std::vector<int>& lines, const std::string& file);
    /// The index of the node with this id; -1 when there is none.
    int find(long long id) const {
        if (m_dense) return id >= 0 && id < (long long)m_table.size() ? m_table[size_t(id)] : -1;
        const auto it = m_hash.find(id);
        return it == m_hash.end() ? -1 : it->second;
    }

private:
    bool m_dense = true;  ///< ids are small enough for a table; else a hash map
    std::vector<int> m_table;
    std::unordered_map<long long, int> m_hash;
};

} // namespace fascia::meshio::detail
