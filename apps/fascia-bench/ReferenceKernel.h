#pragma once
/// The yardstick of the step's targets (docs/performance.md, "Method", the reference kernel): a TLED step for neo-Hookean linear tetrahedra written
/// plainly, in double, on a fixed number of threads, outside the framework (ReferenceKernel.cpp).
/// Per element e (rest volume V0, shape-function derivatives dN_a/dX precomputed), per step:
///   F = I + sum_a u_a (x) dN_a/dX, u = x - X             TLED eq. (1)-(3), TLEDForceField.h
///   S = mu J^(-2/3) (I - I1/3 C^-1) + kappa J (J - 1) C^-1    2 dW/dC of W = mu/2 (I1bar - 3) +
///                                                        kappa/2 (J - 1)^2 (TLED eq. (31)-(32),
///                                                        materials/Laws.h NeoHookeanLaw)
///   f_a = -V0 F S dN_a/dX                                the force on node a
/// each thread adds its elements' forces into its own buffer over the node range they use, then the
/// buffers are summed per node in thread order and the nodes updated by semi-implicit Euler,
///   v += dt f / m, x += dt v   (v = 0 and x = X at fixed nodes),
/// in one parallel region with one barrier. Results depend on the thread count (the sum order), not
/// on the schedule. Written to be fast as well as plain: the element data as structure of arrays,
/// batches of 16 elements through one vector loop (J^(-1/3) by core::invCbrt, fascia/base/FastMath.h, no pow), the
/// gather and the scatter scalar.
#include "fascia/sim/LayoutBytes.h"
#include "fascia/sim/Mechanics.h"

#include <array>
#include <vector>

namespace fascia::bench {

class ReferenceTLED {
public:
    /// tets over rest positions X; mu, kappa (Pa); nodal masses m (kg); fixed nodes.
    ReferenceTLED(const Tetrahedra& tets, const Positions& X, double mu, double kappa, const std::vector<double>& m,
                  const IndexList& fixed, int threads);
    /// Sets positions x and velocities v (v empty: zero).
    void setState(const Positions& x, const Positions& v = {});
    /// f (3 doubles per node) = the internal forces at the current positions.
    void forces(std::vector<double>& f);
    /// One step of length dt: forces, then the node update.
    void step(double dt);
    const std::vector<double>& x() const { return m_x; }
    size_t elementCount() const { return m_count; }
    size_t nodeCount() const { return m_X.size() / 3; }
    /// What a step moves (core::LayoutBytes): the element records; X, x, v, m read, x, v written;
    /// the thread buffers cleared, read and written by the elements, read by the sum.
    core::LayoutBytes layoutBytes() const;

private:
    /// Elements per batch: the stress loop runs over a batch as one vector loop.
    static constexpr int kBatch = 16;
    /// The elements of thread t add into m_buf[t], then f or the update (dt > 0 with Update).
    template <bool Update>
    void run(double dt, double* f);
    /// Forces fe[a][c][k] on node a of element e0 + k, k < n.
    void batchForces(size_t e0, int n, double (&fe)[4][3][kBatch]) const;

    // the elements, sorted by their lowest node, as structure of arrays
    std::vector<int> m_node[4];
    std::vector<double> m_dN[9];  ///< dN_a/dX component c of nodes a = 1..3 at 3 (a - 1) + c; dN_0 = -(dN_1 + dN_2 + dN_3)
    std::vector<double> m_V0;     ///< rest volumes
    size_t m_count = 0;           ///< elements (the arrays above hold kBatch more, zeros)
    std::vector<double> m_X, m_x, m_v, m_invMass;  ///< 3 per node (invMass: 1 per node, 0 when fixed)
    double m_mu, m_kappa;
    int m_threads;
    std::vector<size_t> m_begin;                   ///< elements of thread t: [m_begin[t], m_begin[t + 1])
    std::vector<int> m_lo, m_hi;                   ///< node range of thread t's elements
    std::vector<std::vector<double>> m_buf;        ///< 3 per node of the range
};

} // namespace fascia::bench
