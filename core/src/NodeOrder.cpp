#include "fascia/base/NodeOrder.h"

#include <algorithm>
#include <numeric>

namespace fascia {

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
    std::vector<int> level(n, -1);
    auto bfs = [&](int start, std::vector<int>& out, std::vector<char>& mark) {
        size_t head = out.size();
        out.push_back(start);
        mark[start] = 1;
        while (head < out.size()) {
            const int v = out[head++];
            for (int w : adj[v])
                if (!mark[w]) {
                    mark[w] = 1;
                    out.push_back(w);
                }
        }
    };
    for (int s : seeds) {
        if (seen[s]) continue;
        // pseudo-peripheral start: the least connected node of the last BFS level from s
        std::vector<int> comp;
        std::vector<char> mark = seen;
        bfs(s, comp, mark);
        int start = s;
        // BFS levels from s (comp is in BFS order)
        for (int v : comp) level[v] = -1;
        level[s] = 0;
        int maxLevel = 0;
        for (int v : comp)
            for (int w : adj[v])
                if (level[w] < 0) {
                    level[w] = level[v] + 1;
                    maxLevel = std::max(maxLevel, level[w]);
                }
        for (int v : comp)
            if (level[v] == maxLevel && (start == s || byDegree(v, start))) start = v;
        bfs(start, order, seen);
    }
    std::reverse(order.begin(), order.end());
    return order;
}

} // namespace fascia
