// Tests of the element layer: the 3x3 vocabulary against Eigen, the stress formulas against each
// other and against S = 2 dW/dC by finite differences, groupMaterials parsing, the law dispatch over
// the one list, the block buffers' ordered sum (both layouts) and ElementAssembly's thread
// independence, the node renumbering, the density rule of the stable time step.
#include "fascia/elements/BlockBuffers.h"
#include "fascia/elements/ElementAssembly.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/GroupMaterials.h"
#include "fascia/elements/LawDispatch.h"
#include "fascia/elements/NodeOrder.h"
#include "fascia/elements/Tensor3.h"
#include "fascia/materials/Conformance.h"

#include <catch2/catch.hpp>
#include <omp.h>

#include <Eigen/Dense>
#include <cstring>
#include <algorithm>
#include <numeric>
#include <random>

using namespace fascia;
using namespace fascia::elements;

namespace {

Mat33<double> toM(const Mat3& F) {
    return {F(0, 0), F(0, 1), F(0, 2), F(1, 0), F(1, 1), F(1, 2), F(2, 0), F(2, 1), F(2, 2)};
}
Mat3 toE(const Mat33<double>& F) {
    Mat3 m;
    m << F.xx, F.xy, F.xz, F.yx, F.yy, F.yz, F.zx, F.zy, F.zz;
    return m;
}
Mat3 toE(const Sym33<double>& S) {
    Mat3 m;
    m << S.xx, S.xy, S.xz, S.xy, S.yy, S.yz, S.xz, S.yz, S.zz;
    return m;
}
const Mat3 kF = (Mat3() << 1.2, 0.1, 0.0, -0.05, 0.9, 0.2, 0.03, 0.0, 1.1).finished();

/// A built-in material with its example parameters, initialised.
std::unique_ptr<materials::BaseMaterial> example(const std::string& name) {
    auto m = materials::createBuiltinMaterial(name);
    for (const auto& [k, v] : materials::exampleParameters(name)) m->findParam(k)->read(v, {});
    m->init();
    return m;
}

} // namespace

TEST_CASE("the 3x3 vocabulary agrees with Eigen", "[Tensor3]") {
    const Mat33<double> F = toM(kF);
    CHECK(det(F) == Approx(kF.determinant()).epsilon(1e-14));
    CHECK((toE(cofactor(F)) - kF.determinant() * kF.inverse().transpose()).norm() < 1e-14);
    CHECK((toE(rightCauchyGreen(F)) - kF.transpose() * kF).norm() < 1e-14);
    CHECK((toE(leftCauchyGreen(F)) - kF * kF.transpose()).norm() < 1e-14);
    const auto in = invariants<true>(F);
    const Mat3 C = kF.transpose() * kF;
    CHECK(in.I1 == Approx(C.trace()).epsilon(1e-14));
    CHECK(in.I2 == Approx(0.5 * (C.trace() * C.trace() - (C * C).trace())).epsilon(1e-14));
    CHECK(invariants<false>(F).I2 == 3.0);
    const Vec3 a(0.6, 0.0, 0.8);
    CHECK(fibreInvariant(F, Vec33<double>{a[0], a[1], a[2]}) == Approx(a.dot(C * a)).epsilon(1e-14));
    const Sym33<double> S{1.0, 2.0, 3.0, 0.5, -0.25, 0.125};
    CHECK((toE(firstPiolaOf(F, S)) - kF * toE(S)).norm() < 1e-14);
    const Mat3 sigma = kF * toE(S) * kF.transpose() / kF.determinant();
    CHECK((toE(cauchyStress(F, S, det(F))) - sigma).norm() < 1e-13);
}

TEST_CASE("von Mises stress is zero for a pressure and sqrt 3 tau for a pure shear", "[Tensor3]") {
    CHECK(vonMises(Sym33<double>{-5, -5, -5, 0, 0, 0}) == 0.0);
    CHECK(vonMises(Sym33<double>{0, 0, 0, 2.0, 0, 0}) == Approx(2.0 * std::sqrt(3.0)).epsilon(1e-15));
    CHECK(vonMises(Sym33<double>{7, 0, 0, 0, 0, 0}) == Approx(7.0).epsilon(1e-15));  // uniaxial
}

TEST_CASE("P from the response equals F S and S is 2 dW/dC for every built-in law", "[Tensor3][LawDispatch]") {
    const std::string name = GENERATE(from_range(materials::builtinMaterialNames()));
    CAPTURE(name);
    auto m = example(name);
    const Vec3* da = m->fibreDirection(0);
    const Vec3* db = m->fibreDirection(1);
    const Vec3 a = da ? *da : Vec3(0, 0, 1), b = db ? *db : Vec3(1, 0, 0);
    const auto W = [&](const Mat3& C) {
        // W through the invariants of C (F = sqrt C is not needed: W depends on C only)
        materials::Invariants in;
        in.I1 = C.trace();
        in.I2 = 0.5 * (in.I1 * in.I1 - (C * C).trace());
        in.J = std::sqrt(C.determinant());
        in.I4 = a.dot(C * a);
        in.I6 = b.dot(C * b);
        return materials::conformance::evaluateOne(*m, in, 0.4).W;
    };
    const Mat3 C = kF.transpose() * kF;
    const materials::Invariants in = materials::conformance::invariantsOf(kF, a, b);
    const materials::Response r = materials::conformance::evaluateOne(*m, in, 0.4);
    const Coefficients<double> co{r.dI1, r.dI2, r.dI4, r.dI6, r.dJiso, r.dJvol};
    const Vec33<double> va{a[0], a[1], a[2]}, vb{b[0], b[1], b[2]};
    Sym33<double> Si, Sv;
    secondPiola<true, true, true>(toM(kF), in.I1, in.J, co, va, vb, Si, Sv);
    const Mat3 S = toE(Si + Sv);
    // S = 2 dW/dC by central differences (symmetric perturbations)
    const double scale = S.norm();
    double err = 0;
    const double h = 1e-6;
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j) {
            Mat3 E = Mat3::Zero();
            E(i, j) = E(j, i) = h;
            // dW/dh = dW/dC_ii = S_ii / 2 on the diagonal, dW/dC_ij + dW/dC_ji = S_ij off it
            const double dW = (W(C + E) - W(C - E)) / (2 * h);
            const double expect = (i == j ? 0.5 : 1.0) * S(i, j);
            err = std::max(err, std::abs(dW - expect) / scale);
        }
    CHECK(err < 1e-6);
    const Mat3 P = toE(firstPiola<true, true, true>(toM(kF), in.I1, co, va, vb));
    CHECK((P - kF * S).norm() < 1e-10 * P.norm());
}

TEST_CASE("the law dispatch inlines every entry of the list and only those", "[LawDispatch]") {
    for (const auto& name : materials::builtinMaterialNames()) {
        CAPTURE(name);
        auto m = example(name);
        CHECK(isBuiltinLaw(m.get()));
        const bool picksOwnLaw = selectForLaw(m.get(), [&](auto tag) {
            using Law = typename decltype(tag)::type;
            if constexpr (std::is_same_v<Law, GenericLaw>) return false;
            else return &lawOf<Law>(m.get()) == &static_cast<const materials::Material<Law>*>(m.get())->law();
        });
        CHECK(picksOwnLaw);
    }
    // a material outside the list runs the generic loop
    struct Other : materials::BaseMaterial {
        unsigned uses() const override { return 0; }
        void evaluate(const materials::Invariants*, materials::Response*, size_t, double) const override {}
        double shearModulus() const override { return 1; }
        double bulkModulus() const override { return 1; }
    } other;
    CHECK_FALSE(isBuiltinLaw(&other));
    CHECK(materials::createBuiltinMaterial("NoSuchLaw") == nullptr);
    CHECK(materials::builtinMaterialNames().size() == materials::BuiltinMaterials::size);
}

TEST_CASE("groupMaterials is split into pairs once and remembers an unpaired word", "[GroupMaterials]") {
    const GroupMaterialList l("1 @soft  tumour @stiff");
    REQUIRE(l.pairs.size() == 2);
    CHECK(l.pairs[0] == std::make_pair(std::string("1"), std::string("@soft")));
    CHECK(l.pairs[1] == std::make_pair(std::string("tumour"), std::string("@stiff")));
    CHECK_FALSE(l.odd);
    CHECK(GroupMaterialList("1 @a 2").odd);
    CHECK(GroupMaterialList("").empty());
    CHECK(core::ParamTraits<GroupMaterialList>::format(l) == "1 @soft  tumour @stiff");
}

TEST_CASE("the block buffers add each node's rows in block order and clear them", "[BlockBuffers]") {
    BlockBuffers bb;
    bb.addBlock(0, 2);
    bb.addBlock(1, 3);
    bb.finish(4, {3, 2, 1, 0});  // internal node q is state node 3 - q
    REQUIRE(bb.rows() == 6);
    CHECK(bb.rowCount(1) == 3);
    CHECK(bb.maxRows() == 3);
    for (size_t b = 0; b < 2; ++b)
        for (int q = bb.lo(b); q <= bb.hi(b); ++q)
            for (int c = 0; c < 3; ++c) bb.buffer(b)[4 * (q - bb.lo(b)) + c] = 10.0 * double(b + 1) + q + 0.1 * c;
    std::vector<double> f(12, 1.0);
    bb.sumInto(f.data());
    // internal node 1 (state node 2): block 0 row 1 + block 1 row 0
    CHECK(f[3 * 2 + 0] == 1.0 + (10 + 1) + (20 + 1));
    CHECK(f[3 * 3 + 2] == 1.0 + (10 + 0 + 0.2));  // internal 0 only in block 0
    CHECK(f[3 * 0 + 1] == 1.0 + (20 + 3 + 0.1));  // internal 3 only in block 1
    for (size_t b = 0; b < 2; ++b)
        for (size_t i = 0; i < 4 * bb.rowCount(b); ++i) CHECK(bb.buffer(b)[i] == 0.0);
    const double addBytes = double(bb.stepBytes().buffers);

    // committed buffers: each block's rows written whole, not cleared by the sum
    BlockBuffers cb;
    cb.addBlock(0, 2);
    cb.addBlock(1, 3);
    cb.finish(4, {3, 2, 1, 0}, BlockBuffers::Fill::Commit);
    const std::vector<double> rows(12, 0.5);
    cb.commit(0, rows.data());
    cb.commit(1, rows.data());
    std::fill(f.begin(), f.end(), 0.0);
    cb.sumInto(f.data());
    CHECK(f[3 * 2 + 0] == 1.0);  // in both blocks
    CHECK(f[3 * 3 + 0] == 0.5);
    CHECK(cb.buffer(1)[0] == 0.5);
    CHECK(double(cb.stepBytes().buffers) == addBytes / 2);
}

TEST_CASE("The compact block buffers rewrite each block's nodes to its rows and sum every node's rows in block order",
          "[CompactBlockBuffers]") {
    CompactBlockBuffers cb;
    // block 0: two corners over two elements, internal nodes {3, 1} and {1, 4}: rows 1 3 4
    std::vector<int> a0{3, 1}, a1{1, 4}, b0{4, 0, 4}, c0{4};
    CHECK(cb.addBlock({{a0.data(), 2}, {a1.data(), 2}}) == 0);
    CHECK(cb.addBlock({{b0.data(), 3}}) == 1);
    CHECK(cb.addBlock({{c0.data(), 1}}) == 2);
    CHECK(a0 == std::vector<int>{1, 0});
    CHECK(a1 == std::vector<int>{0, 2});
    CHECK(b0 == std::vector<int>{1, 0, 1});
    cb.finish({4, 3, 2, 1, 0});  // internal node q is state node 4 - q
    REQUIRE(cb.blockCount() == 3);
    CHECK(cb.rows() == 6);
    CHECK(cb.rowBegin(1) == 3);
    CHECK(cb.rowEnd(1) == 5);
    CHECK(cb.rowInternal() == std::vector<int>{1, 3, 4, 0, 4, 4});
    CHECK(cb.directGather());  // 5 nodes: the state's positions are read in place
    std::vector<double> x(15);
    for (size_t i = 0; i < x.size(); ++i) x[i] = 0.5 * double(i);
    const double* xi = cb.positionsIn(x.data());
    CHECK(xi == x.data());
    CHECK(cb.maxRows() == 3);
    BlockScratch scratch;
    scratch.reserve(cb.maxRows(), cb.maxRows());
    for (size_t b = 0; b < 3; ++b) {
        double* rows = scratch.positions(1);
        cb.loadRows(b, xi, rows);
        for (size_t r = 0; r < cb.rowCount(b); ++r) {
            const int state = 4 - cb.rowInternal()[cb.rowBegin(b) + r];
            for (int c = 0; c < 3; ++c) CHECK(rows[4 * r + c] == x[3 * size_t(state) + size_t(c)]);
            CHECK(rows[4 * r + 3] == 0.0);
        }
    }
    // internal node 4 (state node 0) has a row in each block: 1, 1e16, -1e16 sum to 0 in block
    // order ((1 + 1e16) rounds to 1e16), to 1 in the reverse order; each block's forces are
    // committed from a thread's rows, cleared for each block
    const auto commit = [&](size_t b, std::vector<std::pair<size_t, double>> values) {
        double* f = scratch.forces(2, cb.rowCount(b));
        for (auto [i, v] : values) f[i] = v;
        cb.commit(b, f);
    };
    commit(0, {{4 * 2 + 0, 1.0}, {4 * 0 + 2, 3.0}});  // and internal node 1 (state node 3), block 0 only
    commit(1, {{4 * 1 + 0, 1e16}, {4 * 1 + 1, 2.0}});
    commit(2, {{4 * 0 + 0, -1e16}});
    std::vector<double> f(15, 1.0);
    cb.sumInto(f.data());
    CHECK(f[0] == 1.0);
    CHECK(f[1] == 1.0 + 2.0);
    CHECK(f[3 * 3 + 2] == 1.0 + 3.0);
    CHECK(f[3 * 2 + 0] == 1.0);  // internal node 2 is in no block
    // a commit overwrites the block's buffer (nothing to clear between evaluations)
    CHECK(cb.buffer(1)[4] == 1e16);
    commit(1, {{0, 5.0}});
    CHECK(cb.buffer(1)[0] == 5.0);
    for (size_t i = 1; i < 8; ++i) CHECK(cb.buffer(1)[i] == 0.0);
}

TEST_CASE("The compact block buffers copy the positions into internal order on large meshes", "[CompactBlockBuffers]") {
    const int n = 30000;  // above the direct-gather limit (about 21,800 nodes)
    std::vector<int> nodeOf(n);
    for (int q = 0; q < n; ++q) nodeOf[size_t(q)] = n - 1 - q;
    CompactBlockBuffers cb;
    std::vector<int> b0{0, n - 1, 15000}, b1{15000, 7};
    cb.addBlock({{b0.data(), 3}});
    cb.addBlock({{b1.data(), 2}});
    cb.finish(nodeOf);
    CHECK_FALSE(cb.directGather());
    std::vector<double> x(3 * size_t(n));
    for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(double(i));
    const double* xi = cb.positionsIn(x.data());
    REQUIRE(xi != x.data());
    for (int q : {0, 7, 15000, n - 1})
        for (int c = 0; c < 3; ++c) CHECK(xi[4 * q + c] == x[3 * size_t(n - 1 - q) + size_t(c)]);
    std::vector<double> rows(4 * cb.maxRows());
    cb.loadRows(1, xi, rows.data());
    // block 1's rows: internal nodes 7 and 15000
    for (int c = 0; c < 3; ++c) {
        CHECK(rows[size_t(c)] == x[3 * size_t(n - 1 - 7) + size_t(c)]);
        CHECK(rows[size_t(4 + c)] == x[3 * size_t(n - 1 - 15000) + size_t(c)]);
    }
}

TEST_CASE("Reverse Cuthill-McKee numbers a shuffled chain along the chain, the same every time", "[reverseCuthillMcKee]") {
    // a chain of 200 nodes as 2-node elements, labelled at random, and one node no element uses
    const size_t n = 201;
    std::vector<int> label(200);
    std::iota(label.begin(), label.end(), 0);
    std::shuffle(label.begin(), label.end(), std::mt19937(3));
    for (int& l : label) l = l >= 100 ? l + 1 : l;  // node 100 is the unused one
    std::vector<int> links;
    for (size_t i = 0; i + 1 < label.size(); ++i) links.insert(links.end(), {label[i], label[i + 1]});
    const std::vector<int> order = reverseCuthillMcKee(n, {{links.data(), links.size() / 2, 2}});
    REQUIRE(order.size() == n);
    std::vector<int> sorted = order, all(n);
    std::sort(sorted.begin(), sorted.end());
    std::iota(all.begin(), all.end(), 0);
    CHECK(sorted == all);  // a permutation
    std::vector<int> pos(n);
    for (size_t i = 0; i < n; ++i) pos[size_t(order[i])] = int(i);
    int bandwidth = 0;
    for (size_t i = 0; i + 1 < links.size(); i += 2) bandwidth = std::max(bandwidth, std::abs(pos[size_t(links[i])] - pos[size_t(links[i + 1])]));
    CHECK(bandwidth == 1);
    CHECK(reverseCuthillMcKee(n, {{links.data(), links.size() / 2, 2}}) == order);
}

TEST_CASE("Reverse Cuthill-McKee starts from the end of a strip, not from its least connected node", "[reverseCuthillMcKee]") {
    // a strip of 2 x 60 nodes cut into triangles, and one node hanging from its middle by a
    // 2-node element: that node is the least connected, but a numbering from it spreads both ways
    // (bandwidth 5 or more); from a pseudo-peripheral node (an end of the strip) each BFS level
    // holds at most 3 nodes, so no element spans more than 3 positions
    const int L = 60, n = 2 * L + 1, hanging = 2 * L;
    std::vector<int> tris, links{hanging, L};  // hangs from the top node of column L / 2
    for (int i = 0; i + 1 < L; ++i) tris.insert(tris.end(), {2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 1, 2 * i + 3, 2 * i + 2});
    const std::vector<int> order = reverseCuthillMcKee(size_t(n), {{tris.data(), tris.size() / 3, 3}, {links.data(), 1, 2}});
    REQUIRE(order.size() == size_t(n));
    std::vector<int> pos(size_t(n), -1);
    for (size_t i = 0; i < order.size(); ++i) pos[size_t(order[i])] = int(i);
    CHECK(std::count(pos.begin(), pos.end(), -1) == 0);
    int bandwidth = 0;
    for (size_t t = 0; t < tris.size(); t += 3)
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) bandwidth = std::max(bandwidth, std::abs(pos[size_t(tris[t + a])] - pos[size_t(tris[t + b])]));
    CHECK(bandwidth <= 3);
}

TEST_CASE("ElementAssembly gives the same forces with 1 and 2 threads", "[ElementAssembly]") {
    // 3000 random "elements" over 500 nodes, element forces from a fixed formula
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> node(0, 499);
    std::vector<std::array<int, 4>> els(3000);
    for (auto& e : els)
        for (int& v : e) v = node(rng);
    ElementAssembly as;
    as.init(els, 500, 256);
    CHECK(as.blockCount() == 12);
    const auto run = [&](int threads) {
        omp_set_num_threads(threads);
        std::vector<double> f(1500, 0.0);
        as.addForces(els, f.data(), [&](size_t e, Vec3 (&fe)[4]) {
            for (int a = 0; a < 4; ++a) fe[a] = Vec3(std::sin(double(e) + a), 1.0 / (1.0 + e + a), 0.1 * a);
        });
        return f;
    };
    const auto f1 = run(1), f2 = run(2);
    CHECK(std::memcmp(f1.data(), f2.data(), f1.size() * sizeof(double)) == 0);
    // and the forces are the plain sums (to round-off)
    std::vector<double> ref(1500, 0.0);
    for (size_t e = 0; e < els.size(); ++e)
        for (int a = 0; a < 4; ++a) {
            const Vec3 v(std::sin(double(e) + a), 1.0 / (1.0 + e + a), 0.1 * a);
            for (int c = 0; c < 3; ++c) ref[3 * size_t(els[e][a]) + c] += v[c];
        }
    double err = 0;
    for (size_t i = 0; i < ref.size(); ++i) err = std::max(err, std::abs(ref[i] - f1[i]));
    CHECK(err < 1e-12);
}

TEST_CASE("a tetrahedron's rest data: volume, inverse edge matrix and shortest altitude", "[Geometry]") {
    const Positions X = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, 4)};
    CHECK(tetSignedVolume6(X[0], X[1], X[2], X[3]) == Approx(24.0));
    // altitude onto the largest face (the slanted one, area sqrt(61)): 3 V / A
    CHECK(tetAltitude(X[0], X[1], X[2], X[3], 4.0) == Approx(12.0 / std::sqrt(61.0)).epsilon(1e-14));
    CHECK(tetLongestEdge(X[0], X[1], X[2], X[3]) == Approx(5.0));
}
