#pragma once
/// What a reader produces, shared by all formats: the mesh, where its nodes and elements came from
/// (for located validation errors) and its physical groups. Private to the readers.
#include "MeshReaders.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace fascia::meshio::detail {

/// Where elements and nodes came from, for located validation errors.
struct ElementOrigin {
    std::string nodeFile, elementFile;     ///< files holding the nodes / the elements
    std::vector<int> nodeLine;             ///< per node (empty: unknown)
    std::vector<long long> nodeId;         ///< file id per node (empty: the index is the id)
    std::vector<int> tetLine, hexLine;     ///< per element (empty: unknown)
    /// Per node / element of a BINARY file, its byte offset instead of a line (empty: a text file or unknown).
    std::vector<long long> nodeByte, tetByte, hexByte;
    std::vector<long long> tetNumber, hexNumber;  ///< file number per element (empty: none)
    std::string elementWord = "element";   ///< "cell" for VTK files
};

/// The file's id of node `index` (the index itself when the file gave none).
std::string nodeName(const ElementOrigin& o, int index);

/// Collects everything a reader produces.
struct MeshBuilder {
    MeshData mesh;
    ElementOrigin origin;
    ReadReport* report = nullptr;
    std::map<std::pair<int, int>, std::string> names;  ///< (dim, tag) -> name; dim -1: any

    /// Adds the nodes of one element to group (dim, tag); tag 0 is no group.
    void markGroup(int dim, int tag, const int* nodes, size_t n) {
        if (tag == 0) return;
        const std::pair<int, int> key{dim, tag};
        if (m_lastId < 0 || m_lastKey != key) {
            const auto [it, added] = m_groupIds.emplace(key, int(m_lists.size()));
            if (added) m_lists.emplace_back();
            m_lastId = it->second;
            m_lastKey = key;
            if (m_lastAdded.size() != mesh.points.size()) m_lastAdded.assign(mesh.points.size(), -1);
        }
        // elements of a group mostly come together: skip nodes this group just took
        auto& list = m_lists[size_t(m_lastId)];
        for (size_t i = 0; i < n; ++i) {
            int& last = m_lastAdded[size_t(nodes[i])];
            if (last != m_lastId) {
                list.push_back(nodes[i]);
                last = m_lastId;
            }
        }
    }
    /// Counts one element of a kind that is not kept.
    void skip(const std::string& kind) { ++report->skipped[kind]; }

    /// nodeGroups ("physical:<tag>" and names) and groupNames from the collected lists and names.
    void finishGroups();

private:
    std::map<std::pair<int, int>, int> m_groupIds;  ///< (dim, tag) -> index in m_lists
    std::vector<IndexList> m_lists;                 ///< nodes per group, unsorted, maybe repeated
    std::vector<int> m_lastAdded;                   ///< per node: the group that added it last
    int m_lastId = -1;
    std::pair<int, int> m_lastKey{0, 0};
};

} // namespace fascia::meshio::detail
