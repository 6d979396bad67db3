#pragma once
/// Node renumbering for the element loops of the force fields (the element layer's: the core knows
/// no elements). Used by HEML (always) and TLED (when the file's order makes its buffers large).
#include <cstddef>
#include <initializer_list>
#include <vector>

namespace fascia::elements {

/// The node indices of a list of elements: count elements of perElement nodes each, one after the other.
struct ElementNodes {
    const int* nodes = nullptr;
    size_t count = 0;
    int perElement = 0;
};

/// Reverse Cuthill-McKee order of nodes 0..n-1, two nodes being neighbours when an element of the
/// lists holds both (docs/performance.md, lesson 5): entry i is the input node placed at position i. Each
/// connected part starts from a pseudo-peripheral node (the least connected of the last BFS level
/// from its least connected node); neighbours are visited by increasing degree. Deterministic.
std::vector<int> reverseCuthillMcKee(size_t n, std::initializer_list<ElementNodes> elements);

} // namespace fascia::elements
