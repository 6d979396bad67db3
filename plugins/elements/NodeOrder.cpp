#include "fascia/elements/NodeOrder.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <numeric>

namespace fascia::elements {

std::vector<int> reverseCuthillMcKee(size_t n, std::initializer_list<ElementNodes> elements) {
    // the neighbours of each node in compressed rows (adjStart: offsets, n + 1), built through the
    // elements of each node (its incidences) rather than a growing list per node: a few bytes per
    // element instead of hundreds per node
    std::vector<size_t> adjStart(n + 1, 0);
    std::vector<int> adj;
    {
        std::vector<size_t> incStart(n + 1, 0);
        size_t total = 0;
        for (const ElementNodes& list : elements) {
            for (size_t i = 0; i < list.count * static_cast<size_t>(list.perElement); ++i) ++incStart[static_cast<size_t>(list.nodes[i]) + 1];
            total += list.count;
        }
        for (size_t i = 0; i < n; ++i) incStart[i + 1] += incStart[i];
        // incidences: the element (numbered across the lists) of each node occurrence; an element
        // that holds a node twice is listed twice (it makes the node its own neighbour, below)
        // (32 bits: the elements' node indices are ints, and no mesh here has 2^32 elements)
        if (total > std::numeric_limits<std::uint32_t>::max()) throw std::length_error("reverseCuthillMcKee: too many elements");
        std::vector<std::uint32_t> inc(incStart[n]);
        {
            std::vector<size_t> next(incStart.begin(), incStart.end() - 1);
            size_t base = 0;
            for (const ElementNodes& list : elements) {
                for (size_t e = 0; e < list.count; ++e)
                    for (int a = 0; a < list.perElement; ++a)
                        inc[next[static_cast<size_t>(list.nodes[e * static_cast<size_t>(list.perElement) + static_cast<size_t>(a)])]++] = static_cast<std::uint32_t>(base + e);
                base += list.count;
            }
        }
        // an element's nodes from its number across the lists
        const auto nodesOf = [&](size_t g, int& count) {
            for (const ElementNodes& list : elements) {
                if (g < list.count) {
                    count = list.perElement;
                    return list.nodes + g * static_cast<size_t>(list.perElement);
                }
                g -= list.count;
            }
            count = 0;
            return static_cast<const int*>(nullptr);
        };
        // two passes over the incidences: the distinct neighbours' count, then the neighbours. Node
        // v's neighbours are the other nodes of its elements (a pair of positions a != b of an
        // element: v itself too when an element holds it twice)
        std::vector<size_t> mark(n, ~size_t(0));  // the node whose neighbours hold it, this pass
        for (int pass = 0; pass < 2; ++pass) {
            if (pass == 1) {
                std::fill(mark.begin(), mark.end(), ~size_t(0));
                for (size_t i = 0; i < n; ++i) adjStart[i + 1] += adjStart[i];
                adj.resize(adjStart[n]);
            }
            for (size_t v = 0; v < n; ++v) {
                size_t out = adjStart[v];
                const auto add = [&](int w) {
                    if (mark[static_cast<size_t>(w)] == v) return;
                    mark[static_cast<size_t>(w)] = v;
                    if (pass == 0) ++adjStart[v + 1];
                    else adj[out++] = w;
                };
                for (size_t k = incStart[v]; k < incStart[v + 1]; ++k) {
                    int count = 0;
                    const int* t = nodesOf(inc[k], count);
                    int self = 0;
                    for (int b = 0; b < count; ++b)
                        if (t[b] == static_cast<int>(v)) ++self;
                        else add(t[b]);
                    if (self > 1) add(static_cast<int>(v));
                }
            }
        }
    }
    std::vector<int> degree(n);
    for (size_t i = 0; i < n; ++i) degree[i] = static_cast<int>(adjStart[i + 1] - adjStart[i]);
    auto byDegree = [&](int a, int b) { return degree[a] != degree[b] ? degree[a] < degree[b] : a < b; };
    // byDegree is a strict total order: the neighbours' order does not depend on how they were found
    for (size_t i = 0; i < n; ++i) std::sort(adj.begin() + static_cast<long>(adjStart[i]), adj.begin() + static_cast<long>(adjStart[i + 1]), byDegree);

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
            for (size_t k = adjStart[static_cast<size_t>(v)]; k < adjStart[static_cast<size_t>(v) + 1]; ++k)
                if (const int w = adj[k]; !seen[w]) {
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
        if (adjStart[static_cast<size_t>(s)] == adjStart[static_cast<size_t>(s) + 1]) {  // a node no element uses: a part of its own
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
            for (size_t k = adjStart[static_cast<size_t>(v)]; k < adjStart[static_cast<size_t>(v) + 1]; ++k)
                if (const int w = adj[k]; level[w] < 0) {
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
