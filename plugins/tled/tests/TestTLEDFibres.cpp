// TLEDForceField with fibre directions off the axes, on its elastic and viscous force paths
// (the one-term loop that relaxes S and forms P in one pass, and the general loop of several terms
// or series), on tetrahedra and hexahedra, with the directions per group (from the materials) and
// per element (fibreArray, fibreArray2). The reference shares no code with the force field or with
// the law code: per element F = sum_a x_a (x) dN_a/dX, S = F^-1 P with P = dW/dF of the paper energy
// (plugins/materials/tests/LawReference.h), the recurrence of TLED eq. (24), (30) on S kept per
// element in the test, and f_a = -V F S dN_a/dX. Hexahedra are the regular grid's cubes with
// hourglass control off, where the uniform-strain derivatives are the centre-point ones.
#include "../../materials/tests/LawReference.h"
#include "TLEDTestSupport.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace tledtest;

namespace {

/// One element of the reference: its nodes, rest volume and shape-function derivatives.
struct RefElement {
    std::vector<int> nodes;
    std::vector<Vec3> dN;
    double V = 0;
};

std::vector<RefElement> referenceElements(const fascia::MeshData& mesh, double h) {
    std::vector<RefElement> out;
    const Positions& X = mesh.points;
    for (const auto& t : mesh.tetrahedra) {
        RefElement r;
        Mat3 E;
        for (int k = 0; k < 3; ++k) E.col(k) = X[size_t(t[k + 1])] - X[size_t(t[0])];
        const Mat3 Ei = E.inverse();
        r.V = std::abs(E.determinant()) / 6;
        r.nodes.assign(t.begin(), t.end());
        r.dN.resize(4);
        r.dN[0] = -(Ei.row(0) + Ei.row(1) + Ei.row(2)).transpose();
        for (int k = 0; k < 3; ++k) r.dN[size_t(k + 1)] = Ei.row(k).transpose();
        out.push_back(r);
    }
    for (const auto& c : mesh.hexahedra) {
        // an axis-aligned cube of side h: N_a = (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a)/8 gives
        // dN_a/dX = (xi_a, eta_a, zeta_a) / (4 h) at the centre (and as the volume average)
        RefElement r;
        Vec3 lo = X[size_t(c[0])];
        for (int n : c) lo = lo.cwiseMin(X[size_t(n)]);
        r.V = h * h * h;
        r.nodes.assign(c.begin(), c.end());
        for (int n : c) {
            const Vec3 o = (X[size_t(n)] - lo) / h;  // corner offsets 0 or 1
            r.dN.push_back((2 * o - Vec3::Ones()) / (4 * h));
        }
        out.push_back(r);
    }
    return out;
}

/// One Prony series of the reference.
struct Series {
    std::vector<double> alpha, tau;
    bool iso = true, vol = false;
};

/// The reference force field: direct FE with per-element laws and the TLED eq. (30) history on S.
struct Reference {
    std::vector<RefElement> elements;
    std::function<lawref::LawSpec(size_t)> lawOf;
    std::vector<Series> series;
    double dt = 0;
    std::vector<std::vector<std::vector<Mat3>>> Y;  // [series][term][element]

    Positions forces(const Positions& x) {
        if (Y.empty()) {
            Y.resize(series.size());
            for (size_t s = 0; s < series.size(); ++s)
                Y[s].assign(series[s].alpha.size(), std::vector<Mat3>(elements.size(), Mat3::Zero()));
        }
        Positions f(x.size(), Vec3::Zero());
        for (size_t e = 0; e < elements.size(); ++e) {
            const RefElement& r = elements[e];
            Mat3 F = Mat3::Zero();
            for (size_t a = 0; a < r.nodes.size(); ++a) F += x[size_t(r.nodes[a])] * r.dN[a].transpose();
            const lawref::LawSpec law = lawOf(e);
            const Mat3 Fi = F.inverse();
            const Mat3 Siso = Fi * lawref::stressP(law, F, 0.4, lawref::Part::Isochoric);
            const Mat3 Svol = Fi * lawref::stressP(law, F, 0.4, lawref::Part::Volumetric);
            Mat3 S = Siso + Svol;
            for (size_t s = 0; s < series.size(); ++s)
                for (size_t i = 0; i < series[s].alpha.size(); ++i) {
                    const double A = dt * series[s].alpha[i] / (dt + series[s].tau[i]);
                    const double B = series[s].tau[i] / (dt + series[s].tau[i]);
                    const Mat3 R = (series[s].iso ? Siso : Mat3::Zero()) + (series[s].vol ? Svol : Mat3::Zero());
                    Y[s][i][e] = A * R + B * Y[s][i][e];
                    S -= Y[s][i][e];
                }
            const Mat3 P = F * S;
            for (size_t a = 0; a < r.nodes.size(); ++a) f[size_t(r.nodes[a])] -= r.V * P * r.dN[a];
        }
        return f;
    }
};

std::string joined(const std::vector<double>& v) {
    std::string s;
    for (double d : v) s += (s.empty() ? "" : " ") + std::to_string(d);
    return s;
}

/// The viscous set-ups: none; one term (the fused loop), relaxing the isochoric part or both parts;
/// two terms (the general loop); two series, one per part (the general loop).
std::vector<Series> seriesFor(const std::string& visco) {
    if (visco == "one term isochoric") return {{{0.5}, {0.004}, true, false}};
    if (visco == "one term both") return {{{0.4}, {0.003}, true, true}};
    if (visco == "two terms isochoric") return {{{0.3, 0.25}, {0.004, 0.0015}, true, false}};
    if (visco == "two series") return {{{0.3}, {0.004}, true, false}, {{0.2}, {0.002}, false, true}};
    return {};
}

} // namespace

TEST_CASE("TLEDForceField fibre terms off the axes equal direct FE with the paper energy on every force path",
          "[TLEDForceField][viscoelastic]") {
    const std::string type = GENERATE("TransverselyIsotropic", "Orthotropic");
    const bool hexes = GENERATE(false, true);
    const bool perElement = GENERATE(false, true);
    const std::string visco = GENERATE("elastic", "one term isochoric", "one term both", "two terms isochoric", "two series");
    CAPTURE(type, hexes, perElement, visco);

    const double h = 0.01;
    fascia::MeshData mesh;
    mesh.points = gridPoints(3, 3, 2, h);
    if (hexes) mesh.hexahedra = gridHexes(3, 3, 2);
    else mesh.tetrahedra = gridTets(3, 3, 2);
    const size_t ne = hexes ? mesh.hexahedra.size() : mesh.tetrahedra.size();
    std::vector<int>& groups = hexes ? mesh.hexahedronGroup : mesh.tetrahedronGroup;
    for (size_t e = 0; e < ne; ++e) groups.push_back(e < ne / 2 ? 1 : 2);
    std::vector<double> a, b;
    lawref::elementFibres(ne, a, b);
    mesh.cellArrays["fibres"] = a;
    mesh.cellArrays["fibres2"] = b;

    // two materials: off-axis directions of their own (used per group), orthogonal pairs
    lawref::LawSpec m1 = lawref::lawNamed(type), m2 = m1;
    m2.a0 = Vec3(-2, 1, 0.5);
    m2.b0 = Vec3(1, 2, 0);
    m2.eta = 5000;
    Bench bench(mesh.points);
    bench.material(type, m1.params(), "m1");
    bench.material(type, m2.params(), "m2");
    const std::vector<Series> series = seriesFor(visco);
    for (size_t s = 0; s < series.size(); ++s)
        bench.prony(joined(series[s].alpha), joined(series[s].tau),
                    series[s].iso && series[s].vol ? "both" : series[s].iso ? "isochoric" : "volumetric", "visco" + std::to_string(s));
    auto& ff = bench.forceField({}, {}, {{"groupMaterials", "1 @m1 2 @m2"}, {"hourglassStiffness", "0"}});
    ff.m_mesh.set(mesh);
    if (perElement) {
        setParams(ff, {{"fibreArray", "fibres"}});
        if (type == "Orthotropic") setParams(ff, {{"fibreArray2", "fibres2"}});
    }
    ff.init();
    const double dt = 1e-3;
    ff.dtChanged(dt);

    Reference ref;
    ref.elements = referenceElements(mesh, h);
    ref.series = series;
    ref.dt = dt;
    ref.lawOf = [&](size_t e) {
        lawref::LawSpec l = groups[e] == 1 ? m1 : m2;
        if (perElement) {
            l.a0 = lawref::fibreOf(a, e);
            l.b0 = lawref::fibreOf(b, e);
        }
        return l;
    };
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n = 0; n < 4; ++n) {
        // a different non-homogeneous deformation at every step (the history is checked too)
        const Mat3 A = (Mat3() << 1.05 + 0.02 * n, 0.06, -0.02, 0.03, 0.96 - 0.01 * n, 0.04, -0.01, 0.02, 1.02).finished();
        for (size_t i = 0; i < mesh.points.size(); ++i)
            bench.state->x()[i] = A * mesh.points[i] + 4e-4 * Vec3(u(rng), u(rng), u(rng));
        const Positions f = bench.forces(n * dt);
        const Positions r = ref.forces(bench.state->x());
        CAPTURE(n);
        CHECK(lawref::relativeDifference(f, r) < 1e-9);
    }
}

TEST_CASE("TLEDForceField fibreArray2 sets the second fibre direction per element", "[TLEDForceField]") {
    // the same mesh with and without the second array: the forces must follow b0 from the array, not
    // the material's direction2
    const bool hexes = GENERATE(false, true);
    const double h = 0.01;
    fascia::MeshData mesh;
    mesh.points = gridPoints(2, 2, 2, h);
    if (hexes) mesh.hexahedra = gridHexes(2, 2, 2);
    else mesh.tetrahedra = gridTets(2, 2, 2);
    const size_t ne = hexes ? mesh.hexahedra.size() : mesh.tetrahedra.size();
    std::vector<double> a, b;
    lawref::elementFibres(ne, a, b);
    mesh.cellArrays["fibres"] = a;
    mesh.cellArrays["fibres2"] = b;
    const lawref::LawSpec law = lawref::lawNamed("Orthotropic");
    auto run = [&](bool second) {
        Bench bench(mesh.points);
        bench.material("Orthotropic", law.params(), "m");
        auto& ff = bench.forceField({}, {}, {{"fibreArray", "fibres"}, {"hourglassStiffness", "0"}});
        ff.m_mesh.set(mesh);
        if (second) setParams(ff, {{"fibreArray2", "fibres2"}});
        ff.init();
        const Mat3 A = (Mat3() << 1.08, 0.05, 0.0, -0.03, 0.94, 0.04, 0.02, 0.0, 1.03).finished();
        bench.deform(A);
        return bench.forces();
    };
    Reference ref;
    ref.elements = referenceElements(mesh, h);
    ref.lawOf = [&](size_t e) {
        lawref::LawSpec l = law;
        l.a0 = lawref::fibreOf(a, e);
        l.b0 = lawref::fibreOf(b, e);
        return l;
    };
    Positions x = mesh.points;
    const Mat3 A = (Mat3() << 1.08, 0.05, 0.0, -0.03, 0.94, 0.04, 0.02, 0.0, 1.03).finished();
    for (auto& p : x) p = A * p;
    const Positions withArray = run(true), without = run(false), r = ref.forces(x);
    CAPTURE(hexes);
    CHECK(lawref::relativeDifference(withArray, r) < 1e-9);
    CHECK(lawref::relativeDifference(without, r) > 1e-3);
}
