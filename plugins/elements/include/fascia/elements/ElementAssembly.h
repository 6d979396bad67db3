#pragma once
/// Multi-threaded, deterministic force assembly for a force field that computes its element forces
/// one element at a time (an out-of-tree force field, a prototype): the elements are sorted by their
/// lowest node and split into fixed blocks with BlockBuffers, so that the forces are bitwise the same
/// for any thread count. Header-only (the caller compiles the loop, with its OpenMP flags).
///
///   m_assembly.init(m_tets, nodeCount);                       // sorts m_tets, makes the blocks
///   m_assembly.addForces(m_tets, f, [&](size_t e, Vec3 (&fe)[4]) { fe[a] = force on node a; });
#include "fascia/base/Types.h"
#include "fascia/elements/BlockBuffers.h"

#include <algorithm>
#include <array>
#include <vector>

namespace fascia::elements {

class ElementAssembly {
public:
    /// Sorts the elements by their lowest node (stable) and makes fixed blocks of blockSize elements.
    template <size_t NN>
    void init(std::vector<std::array<int, NN>>& elements, size_t nodeCount, size_t blockSize = 1024) {
        std::stable_sort(elements.begin(), elements.end(), [](const auto& a, const auto& b) {
            return *std::min_element(a.begin(), a.end()) < *std::min_element(b.begin(), b.end());
        });
        m_blockSize = blockSize;
        m_buffers = BlockBuffers{};
        for (size_t b = 0; b < elements.size(); b += blockSize) {
            int lo = static_cast<int>(nodeCount), hi = -1;
            for (size_t e = b; e < std::min(elements.size(), b + blockSize); ++e)
                for (int v : elements[e]) lo = std::min(lo, v), hi = std::max(hi, v);
            m_buffers.addBlock(lo, hi);
        }
        m_buffers.finish(nodeCount);
    }

    /// f (3 doubles per node) += sum over elements of forces(e, fe): fe[a] the force on the element's
    /// node a. Runs the blocks on all threads; each adds into its own buffer; sums in block order.
    template <size_t NN, class Forces>
    void addForces(const std::vector<std::array<int, NN>>& elements, double* f, Forces&& forces) {
        const long nb = static_cast<long>(m_buffers.blockCount());
#pragma omp parallel if (nb > 1)
        {
#pragma omp for schedule(dynamic, 1)
            for (long b = 0; b < nb; ++b) {
                double* buf = m_buffers.buffer(static_cast<size_t>(b));
                const int lo = m_buffers.lo(static_cast<size_t>(b));
                const size_t end = std::min(elements.size(), static_cast<size_t>(b + 1) * m_blockSize);
                for (size_t e = static_cast<size_t>(b) * m_blockSize; e < end; ++e) {
                    Vec3 fe[NN];
                    for (auto& v : fe) v.setZero();
                    forces(e, fe);
                    for (size_t a = 0; a < NN; ++a)
                        for (int c = 0; c < 3; ++c) buf[4 * static_cast<size_t>(elements[e][a] - lo) + c] += fe[a][c];
                }
            }
            m_buffers.sumInto(f);
        }
    }

    size_t blockCount() const { return m_buffers.blockCount(); }

private:
    BlockBuffers m_buffers;
    size_t m_blockSize = 1024;
};

} // namespace fascia::elements
