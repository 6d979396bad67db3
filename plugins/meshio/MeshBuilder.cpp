#include "MeshBuilder.h"

#include <algorithm>

namespace fascia::meshio::detail {

std::string nodeName(const ElementOrigin& o, int index) {
    if (index >= 0 && size_t(index) < o.nodeId.size()) return std::to_string(o.nodeId[size_t(index)]);
    return std::to_string(index);
}

void MeshBuilder::finishGroups() {
    auto sortUnique = [](IndexList& l) {
        std::sort(l.begin(), l.end());
        l.erase(std::unique(l.begin(), l.end()), l.end());
    };
    auto merged = [&](IndexList a, const IndexList& b) {
        a.insert(a.end(), b.begin(), b.end());
        sortUnique(a);
        return a;
    };
    for (auto& l : m_lists) sortUnique(l);
    std::map<int, IndexList> byTag;
    for (const auto& [key, id] : m_groupIds) {
        auto& dst = byTag[key.second];
        dst = dst.empty() ? m_lists[size_t(id)] : merged(dst, m_lists[size_t(id)]);
    }
    for (auto& [tag, l] : byTag) mesh.nodeGroups["physical:" + std::to_string(tag)] = std::move(l);
    // names in (dim, tag) order: for a tag named in several dimensions the highest one names it
    for (const auto& [key, name] : names) {
        IndexList nodes = mesh.nodeGroups[name];  // a name given to several groups gathers them
        for (const auto& k : {key, std::pair<int, int>{-1, key.second}}) {  // -1: dimension not known
            const auto it = m_groupIds.find(k);
            if (it != m_groupIds.end()) nodes = merged(std::move(nodes), m_lists[size_t(it->second)]);
        }
        mesh.nodeGroups[name] = std::move(nodes);
        mesh.groupNames[key.second] = name;
    }
    m_groupIds.clear();
    m_lists.clear();
    m_lastAdded.clear();
    m_lastId = -1;
}

} // namespace fascia::meshio::detail
