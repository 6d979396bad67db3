#include "fascia/elements/NodeOrder.h"

#include <algorithm>
#include <numeric>

namespace fascia::elements {

std::vector<int> reverseCuthillMcKee(size_t n, std::initializer_list<ElementNodes> elements) {
    std::vector<std::vector<int>> adj(n);
    for (const ElementNodes& list : elements)
        for (size_t e = 0; e < list.count; ++e) {
            const int* t = list.nodes + e * static_cast<size_t>(list.perElement);
            for (int a = 0; a < list.perElement; ++a)
                for (int b = 0; b < list.perElement; ++b)
                    if (a != b) adj[static_cast<size_t>(t[a])].push_back(t[b]);
        }
    std::vector<int> degree(n);
    for (size_t i = 0; i < n; ++i) {
        auto& v = adj[i];
        std::sort(v.begin(), v.end());
        v.erase(std::unique(v.begin(), v.end()), v.end());
        degree[i] = int(v.size());
    }
    auto byDegree = [&](int a, int b) { return degree[a] != degree[b] ? degree[a] < degree[b] : a < b; };
    for (auto& v : adj) std::sort(v.begin(), v.end(), byDegree);

    std::vector<int> seeds(n);
    std::iota(seeds.begin(), seeds.end(), 0);
    std::sort(seeds.begin(), seeds.end(), byDegree);

    std::vector<char> seen(n, 0);
    std::vector<int> order;
    order.reserve(n);
    auto bfs = [&](int start) {
        size_t head = order.size();
        order.push_back(start);
        seen[start] = 1;
        while (head < order.size()) {
            const int v = order[head++];
            for (int w : adj[v])
                if (!seen[w]) {
                    seen[w] = 1;
                    order.push_back(w);
                }
        }
    };
    // BFS distance from the first node of each connected part (every node belongs to one part, so
    // each is set once; -1: not reached yet)
    std::vector<int> level(n, -1);
    std::vector<int> part;
    for (int s : seeds) {
        if (seen[s]) continue;
        if (adj[s].empty()) {  // a node no element uses: a part of its own
            seen[s] = 1;
            order.push_back(s);
            continue;
        }
        // pseudo-peripheral start: the least connected node of the last BFS level from s
        part.assign(1, s);
        level[s] = 0;
        int maxLevel = 0;
        for (size_t head = 0; head < part.size(); ++head) {
            const int v = part[head];
            for (int w : adj[v])
                if (level[w] < 0) {
                    level[w] = level[v] + 1;
                    maxLevel = std::max(maxLevel, level[w]);
                    part.push_back(w);
                }
        }
        int start = s;
        for (int v : part)
            if (level[v] == maxLevel && (start == s || byDegree(v, start))) start = v;
        bfs(start);
    }
    std::reverse(order.begin(), order.end());
    return order;
}

} // namespace fascia::elements
