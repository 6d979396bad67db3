// The SurfaceTool and its signed distance: the grid and the exact refinement against the exact
// distance of voxel shapes, a tessellated box as a plate (the PlaneTool's result), a tessellated
// sphere indenting a block (between the SphereTools of its inradius and its radius), force and
// torque about the reference point, the same result on 1 and 2 threads, and the grid's memory limit.
#include "ContactTestSupport.h"
#include "DistanceGrid.h"
#include "SurfaceMeshes.h"
#include "SurfaceTool.h"
#include "fascia/base/Format.h"
#include "fascia/surface/TriangleSurface.h"

#include <omp.h>

#include <random>

using namespace contacttest;
using namespace surfacetest;
using fascia::contact::DistanceGrid;
using fascia::contact::SurfaceTool;
using fascia::contact::TriangleTree;
using fascia::core::formatNumber;

namespace {

/// The point of triangle t of m at barycentric weights a (along its first edge) and b (its second).
template <class Mesh, class Triangle>
Vec3 onTriangle(const Mesh& m, const Triangle& t, double a, double b) {
    const Vec3& p0 = m.points[size_t(t[0])];
    return p0 + a * (m.points[size_t(t[1])] - p0) + b * (m.points[size_t(t[2])] - p0);
}

/// Checks grid and query against the exact distance of the voxels at `count` points spread over
/// the grid, and at points near the surface: near it the query is exact, farther within the
/// interpolation's bound, and the sign is always right.
void checkAgainstExact(const Voxels& shape, int resolution, int count) {
    const Mesh m = shape.surface();
    const TriangleTree tree(m.points, m.triangles);
    const DistanceGrid grid(tree, resolution);
    const double h = grid.cell(), size = (tree.hi() - tree.lo()).norm();
    // the stored values are the exact distances (as floats)
    const auto n = grid.counts();
    for (long long k = 0; k < n[2]; k += 3)
        for (long long j = 0; j < n[1]; j += 2)
            for (long long i = 0; i < n[0]; ++i) {
                const Vec3 p = grid.origin() + h * Vec3(double(i), double(j), double(k));
                REQUIRE(std::abs(grid.at(i, j, k) - shape.distance(p)) < 1e-6 * size);
            }
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    const Vec3 lo = grid.origin(), span = h * Vec3(double(n[0] - 1), double(n[1] - 1), double(n[2] - 1));
    int near = 0;
    for (int q = 0; q < count; ++q) {
        Vec3 p = lo + span.cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
        if (q % 2) {  // half the points within half a cell of the surface: a random surface point, moved off along a random direction
            const auto& t = m.triangles[size_t(q / 2) % m.triangles.size()];
            const double a = u(rng), b = u(rng) * (1 - a);
            const Vec3 s = onTriangle(m, t, a, b);
            p = s + (u(rng) - 0.5) * h * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
        }
        const double exact = shape.distance(p);
        Vec3 normal;
        const double d = grid.query(p, normal);
        CAPTURE(p.transpose(), exact, d, h);
        if (std::abs(exact) < 0.25 * h) {  // refined for certain: the interpolation is within sqrt(3) h of it, the band 2 h
            ++near;
            REQUIRE(std::abs(d - exact) < 1e-12 * size);
            REQUIRE(std::abs(normal.norm() - 1) < 1e-12);
            // projected along the normal, the point lands on the surface
            REQUIRE(std::abs(shape.distance(p - d * normal)) < 1e-12 * size);
        } else {
            REQUIRE(std::abs(d - exact) < std::sqrt(3.0) * h + 1e-6 * size);
            REQUIRE((d > 0) == (exact > 0));
        }
    }
    CHECK(near > count / 8);
}

/// The unit cube of the static plate test (tests/verification/TestContactStatics.cpp) on rollers at
/// xmin, ymin and zmin, pressed from z = 1 to 0.8 along keyframes by `tool`.
std::string plateScene(const std::string& tool) {
    return R"(<Node name="root" dt="1">
  <Node name="cube">
    <GridMesh name="grid" min="0 0 0" max="1 1 1" resolution="3 3 3" element="tetrahedra6"/>
    <MechanicalObject name="state"/>
    <LumpedMass density="1000"/>
    <NeoHookean name="mat" mu="1000" kappa="5000"/>
    <HEMLForceField name="ff"/>
    <DynamicRelaxation name="dr" tolerance="1e-11" displacementTolerance="1e-11"/>
    <FixedConstraint name="xmin" group="xmin" directions="1 0 0"/>
    <FixedConstraint name="ymin" group="ymin" directions="0 1 0"/>
    <FixedConstraint name="zmin" group="zmin" directions="0 0 1"/>
    )" + tool + R"( keyTimes="0 4" keyPositions="0 0 1  0 0 0.8"/>
  </Node>
</Node>)";
}

} // namespace

TEST_CASE("The distance grid and its refinement give a box's exact signed distance inside, outside and near edges and vertices", "[SurfaceTool][DistanceGrid]") {
    // 12 triangles, and a box of 4 x 3 x 2 voxels (vertices inside flat faces and on edges)
    checkAgainstExact(Voxels::box(Vec3(-0.1, 0.2, 0.3), Vec3(0.3, 0.5, 0.4), 1, 1, 1), 24, 3000);
    checkAgainstExact(Voxels::box(Vec3(0, 0, 0), Vec3(0.04, 0.03, 0.02), 4, 3, 2), 20, 3000);
    // points at the box's corner and edges, outside, exactly
    const Voxels box = Voxels::box(Vec3(0, 0, 0), Vec3(1, 1, 1), 1, 1, 1);
    const Mesh m = box.surface();
    const TriangleTree tree(m.points, m.triangles);
    const DistanceGrid grid(tree, 16);
    Vec3 n;
    CHECK(grid.query(Vec3(1.01, 1.02, 1.03), n) == Approx(std::sqrt(0.01 * 0.01 + 0.02 * 0.02 + 0.03 * 0.03)).epsilon(1e-13));
    CHECK((n - Vec3(0.01, 0.02, 0.03).normalized()).norm() < 1e-12);
    CHECK(grid.query(Vec3(0.5, -0.03, 1.04), n) == Approx(0.05).epsilon(1e-13));
    CHECK((n - Vec3(0, -0.6, 0.8)).norm() < 1e-12);
    CHECK(grid.query(Vec3(0.5, 0.5, 0.99), n) == Approx(-0.01).epsilon(1e-12));
    CHECK((n - Vec3(0, 0, 1)).norm() < 1e-12);
    CHECK(grid.query(Vec3(1, 1, 1), n) == Approx(0).margin(1e-15));  // on a corner: the vertex's pseudonormal
    CHECK((n - Vec3(1, 1, 1).normalized()).norm() < 1e-12);
    CHECK(grid.query(Vec3(5, 0.5, 0.5), n) > 3.9);  // outside the grid: below the exact 4, above the margin
}

TEST_CASE("The signed distance of a notched cube is exact at its concave edges and vertex", "[SurfaceTool][DistanceGrid]") {
    // a 2 x 2 x 2 voxel cube without its top corner voxel: three concave edges meet at a concave vertex
    Voxels notched = Voxels::box(Vec3(0, 0, 0), Vec3(0.02, 0.02, 0.02), 2, 2, 2);
    notched.full[7] = 0;
    checkAgainstExact(notched, 32, 4000);
    const Mesh m = notched.surface();
    const TriangleTree tree(m.points, m.triangles);
    const DistanceGrid grid(tree, 32);
    Vec3 n;
    CHECK(grid.query(Vec3(0.0105, 0.0105, 0.0105), n) == Approx(0.0005).epsilon(1e-12));  // above the concave vertex, in the notch
    CHECK(grid.query(Vec3(0.0095, 0.0095, 0.0095), n) == Approx(-std::sqrt(3.0) * 0.0005).epsilon(1e-12));  // under it, in the solid
}

TEST_CASE("A tessellated box as a plate gives the PlaneTool's uniaxial compression", "[SurfaceTool][PlaneTool][DynamicRelaxation]") {
    // the box's bottom face (z = 0 in the tool's frame, 4 x 4 voxels: 32 triangles on it, 64 in
    // all with the sides) is the plate's plane; it is larger than the bulging top face
    TempDir dir("plate");
    const std::string obj = writeObj(dir.file("plate.obj"), Voxels::box(Vec3(-0.5, -0.5, 0), Vec3(1.5, 1.5, 0.5), 4, 4, 1).surface());
    auto plane = Simulation::fromString(plateScene("<PlaneTool name=\"plate\" normal=\"0 0 -1\""), "scene.xml");
    auto surf = Simulation::fromString(plateScene("<SurfaceTool name=\"plate\" mesh=\"" + obj + "\" resolution=\"32\""), "scene.xml");
    for (int step = 0; step < 4; ++step) {
        plane->step();
        surf->step();
        const Vec3 fp = toolOf(*plane, "plate").force(), fs = toolOf(*surf, "plate").force();
        CAPTURE(step, fp.transpose(), fs.transpose());
        CHECK(fs[2] > 0);  // the cube pushes the plate up
        CHECK((fs - fp).norm() < 1e-6 * fp.norm());
        CHECK(toolOf(*surf, "plate").contactCount() == 16);
        const Positions &xp = plane->state("state").x(), &xs = surf->state("state").x();
        double worst = 0;
        for (size_t i = 0; i < xp.size(); ++i) worst = std::max(worst, (xp[i] - xs[i]).norm());
        CHECK(worst < 1e-6);
    }
    // the top face is on the plate: z = 0.8
    for (int i : toolOf(*surf, "plate").surfaceNodes())
        if (surf->state("state").x0()[size_t(i)][2] == 1) CHECK(std::abs(surf->state("state").x()[size_t(i)][2] - 0.8) < 1e-9);
}

TEST_CASE("A tessellated sphere indents a block with a force between the SphereTools of its inradius and its radius", "[SurfaceTool][SphereTool]") {
    // a 5120-triangle icosphere of radius 30 mm pressed 3 mm into the top of a 100 x 100 x 50 mm block
    // (base fixed) in two load steps; its faces lie between the spheres of its inradius and its radius
    const double R = 0.03, d = 0.003;
    const Vec3 c(0.05, 0.05, 0.05 + R - d);
    const Mesh ball = icosphere(4, R, Vec3::Zero());
    REQUIRE(ball.triangles.size() == 5120);
    const double rin = inradius(ball, Vec3::Zero());
    CAPTURE(R - rin);
    REQUIRE(R - rin < 0.02 * d);
    TempDir dir("ball");
    const std::string obj = writeObj(dir.file("ball.obj"), ball);
    auto scene = [&](const std::string& tool) {
        const std::string xy = formatNumber(c[0], 17) + " " + formatNumber(c[1], 17) + " ";
        const std::string start = xy + formatNumber(c[2] + d, 17), end = xy + formatNumber(c[2], 17);
        return blockScene("<SemiImplicitEuler damping=\"60\"/>", "    <FixedConstraint name=\"base\" group=\"zmin\"/>\n",
                          "  " + tool + " body=\"@block/state\" keyTimes=\"0 0.4\" keyPositions=\"" + start + "  " + end + "\"/>\n",
                          "dt=\"auto\"", "12 12 6");
    };
    auto force = [&](const std::string& tool) {
        auto sim = Simulation::fromString(scene(tool), "scene.xml");
        sim->runUntil(0.8);
        return toolOf(*sim, "ball").force()[2];
    };
    const double outer = force("<SphereTool name=\"ball\" radius=\"" + formatNumber(R, 17) + "\"");
    const double inner = force("<SphereTool name=\"ball\" radius=\"" + formatNumber(rin, 17) + "\"");
    const double surf = force("<SurfaceTool name=\"ball\" mesh=\"" + obj + "\" resolution=\"24\"");  // (the sphere's centre is equally far from every triangle: the costliest grid to build)
    CAPTURE(outer, inner, surf);
    CHECK(inner > 0);  // the block pushes the ball up
    CHECK(inner < outer);
    CHECK(surf > inner * (1 - 1e-3));
    CHECK(surf < outer * (1 + 1e-3));
    CHECK(std::abs(surf - outer) < 0.03 * outer);
}

TEST_CASE("A surface tool's force and torque about its reference point are those of the plane it presses with", "[SurfaceTool][PlaneTool][RigidTool]") {
    // a box's bottom face, wider than the block, tilted by 6 degrees about x, pressed into the
    // block's top: its y < 0.05 half touches; the tool's reference point (its pose's position) is at y = 0.06
    TempDir dir("torque");
    const std::string obj = writeObj(dir.file("box.obj"), Voxels::box(Vec3(-0.08, -0.08, 0), Vec3(0.12, 0.06, 0.03), 2, 2, 1).surface());
    const std::string pose = "orientation=\"0.99863 0.05234 0 0\" keyTimes=\"0 0.3\" keyPositions=\"0.03 0.06 0.06  0.03 0.06 0.051\"";
    auto run = [&](const std::string& tool) {
        auto sim = Simulation::fromString(
            blockScene("<SemiImplicitEuler damping=\"60\"/>", "    <FixedConstraint name=\"base\" group=\"zmin\"/>\n",
                       "  " + tool + " body=\"@block/state\" " + pose + "/>\n", "dt=\"auto\"", "6 6 3"),
            "scene.xml");
        sim->runUntil(0.4);
        return sim;
    };
    auto plane = run("<PlaneTool name=\"tool\" normal=\"0 0 -1\"");
    auto surf = run("<SurfaceTool name=\"tool\" mesh=\"" + obj + "\" resolution=\"16\"");
    RigidTool &tp = toolOf(*plane, "tool"), &ts = toolOf(*surf, "tool");
    REQUIRE(ts.contactCount() > 3);
    CHECK(ts.contactCount() == tp.contactCount());
    CAPTURE(tp.force().transpose(), ts.force().transpose(), tp.torque().transpose(), ts.torque().transpose());
    CHECK((ts.force() - tp.force()).norm() < 1e-8 * tp.force().norm());
    CHECK((ts.torque() - tp.torque()).norm() < 1e-8 * tp.torque().norm());
    // the torque is the contact forces' moment about the pose's position; all along the normal: no twist about it
    const Positions& x = surf->state("state").x();
    Vec3 t = Vec3::Zero();
    for (size_t i = 0; i < x.size(); ++i) t -= (x[i] - ts.pose().position).cross(ts.contactForces()[i]);
    CHECK((t - ts.torque()).norm() < 1e-3 * t.norm());  // (the nodes moved a little since the forces)
    CHECK(ts.torque().norm() > 0.01 * ts.force().norm() * 0.01);
    const Vec3 normal = ts.pose().orientation * Vec3(0, 0, -1);
    CHECK(std::abs(ts.torque().dot(normal)) < 1e-9 * ts.torque().norm());
    CHECK(std::abs(ts.force().normalized().dot(normal)) == Approx(1).epsilon(1e-9));
}

TEST_CASE("A SurfaceTool from a .vtp presses like the same surface from .stl: the same force and torque", "[SurfaceTool][RigidTool]") {
    // the tilted box of the test above, as ASCII STL and as .vtp (the format Fascia writes surfaces
    // in): the same triangles, their points in another order (STL merges them as they come)
    TempDir dir("vtp");
    const Mesh box = Voxels::box(Vec3(-0.08, -0.08, 0), Vec3(0.12, 0.06, 0.03), 2, 2, 1).surface();
    const std::string stl = writeStl(dir.file("box.stl"), box), vtp = writeVtp(dir.file("box.vtp"), box);
    auto scene = [&](const std::string& mesh) {
        return blockScene("<SemiImplicitEuler damping=\"60\"/>", "    <FixedConstraint name=\"base\" group=\"zmin\"/>\n",
                          "  <SurfaceTool name=\"tool\" mesh=\"" + mesh + "\" resolution=\"16\" body=\"@block/state\" "
                          "orientation=\"0.99863 0.05234 0 0\" keyTimes=\"0 0.3\" keyPositions=\"0.03 0.06 0.06  0.03 0.06 0.051\"/>\n",
                          "dt=\"auto\"", "6 6 3");
    };
#if FASCIA_CONTACT_TEST_WITH_VTK
    auto fromStl = Simulation::fromString(scene(stl), "scene.xml"), fromVtp = Simulation::fromString(scene(vtp), "scene.xml");
    fromStl->runUntil(0.4);
    fromVtp->runUntil(0.4);
    RigidTool &a = toolOf(*fromStl, "tool"), &b = toolOf(*fromVtp, "tool");
    REQUIRE(a.contactCount() > 3);
    CHECK(b.contactCount() == a.contactCount());
    CAPTURE(a.force().transpose(), b.force().transpose(), a.torque().transpose(), b.torque().transpose());
    CHECK((b.force() - a.force()).norm() <= 1e-12 * a.force().norm());
    CHECK((b.torque() - a.torque()).norm() <= 1e-12 * a.torque().norm());
#else
    CHECK_THAT(errorOf(scene(vtp)), Catch::Contains(vtp + ": error: this build has no VTK support") &&
                                        Catch::Contains("read by SurfaceTool 'tool' at scene.xml:2"));
#endif
}

TEST_CASE("A surface tool's grid and contact forces are bitwise the same with 1 and 2 threads", "[SurfaceTool][RigidTool]") {
    TempDir dir("threads");
    const std::string ball = writeObj(dir.file("ball.obj"), icosphere(3, 0.02, Vec3::Zero()));
    const std::string probe = std::string(FASCIA_SOURCE_DIR) + "/scenes/meshes/probe.obj";
    auto run = [&](int threads) {
        omp_set_num_threads(threads);
        auto sim = Simulation::fromString(
            blockScene("<SemiImplicitEuler damping=\"20\"/>", "    <FixedConstraint name=\"base\" group=\"zmin\"/>\n",
                       "  <SurfaceTool name=\"ball\" mesh=\"" + ball + "\" body=\"@block/state\" keyTimes=\"0 0.02\" "
                       "keyPositions=\"0.03 0.05 0.07  0.03 0.05 0.066\" staticFriction=\"0.3\"/>\n"
                       "  <SurfaceTool name=\"probe\" mesh=\"" + probe + "\" body=\"@block/state\" orientation=\"0.995 0 0.0998 0\" resolution=\"96\" "
                       "keyTimes=\"0 0.02\" keyPositions=\"0.075 0.05 0.0505  0.075 0.05 0.0485\"/>\n",
                       "dt=\"auto\"", "16 16 8"),
            "scene.xml");
        sim->run(30);
        auto* grid = dynamic_cast<SurfaceTool&>(toolOf(*sim, "probe")).grid();
        const auto n = grid->counts();
        std::vector<float> phi;
        for (long long k = 0; k < n[2]; ++k)
            for (long long j = 0; j < n[1]; ++j)
                for (long long i = 0; i < n[0]; ++i) phi.push_back(grid->at(i, j, k));
        RigidTool &b = toolOf(*sim, "ball"), &p = toolOf(*sim, "probe");
        struct Out { Vec3 fb, tb, fp, tp; Positions cb, cp, x; std::vector<float> phi; size_t np; };
        return Out{b.force(), b.torque(), p.force(), p.torque(), b.contactForces(), p.contactForces(), sim->state("state").x(), phi,
                   p.contactCount()};
    };
    const int before = omp_get_max_threads();
    const auto one = run(1), two = run(2);
    omp_set_num_threads(before);
    CHECK(one.fb.norm() > 0);
    CHECK(one.np > 4);
    CHECK(one.phi == two.phi);
    CHECK(one.fb == two.fb);
    CHECK(one.tb == two.tb);
    CHECK(one.fp == two.fp);
    CHECK(one.tp == two.tp);
    CHECK(one.cb == two.cb);
    CHECK(one.cp == two.cp);
    CHECK(one.x == two.x);
}

namespace {
/// The grid's query (the cell lists) against the same query through the whole tree, at `count`
/// points near the surface of m (a random surface point moved by up to 2.5 cells along a random
/// direction) and spread over the grid: bitwise the same distance and normal.
void checkListsAgainstTree(const Mesh& m, int resolution, int count) {
    const TriangleTree tree(m.points, m.triangles);
    const DistanceGrid grid(tree, resolution);
    const double h = grid.cell();
    const auto n = grid.counts();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    const Vec3 lo = grid.origin(), span = h * Vec3(double(n[0] - 1), double(n[1] - 1), double(n[2] - 1));
    int band = 0;
    for (int q = 0; q < count; ++q) {
        Vec3 p = lo + span.cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
        if (q % 4) {
            const auto& t = m.triangles[size_t(rng() % m.triangles.size())];
            const double a = u(rng), b = u(rng) * (1 - a);
            const Vec3 s = onTriangle(m, t, a, b);
            // on the surface exactly, or off it by up to 2.5 cells
            const double off = q % 8 == 1 ? 0.0 : 5 * (u(rng) - 0.5) * h;
            p = s + off * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
        }
        Vec3 nl, nt;
        const double dl = grid.query(p, nl), dt = grid.queryTree(p, nt);
        CAPTURE(q, p.transpose(), dl, dt, h);
        REQUIRE(dl == dt);
        REQUIRE(nl == nt);
        if (std::abs(dl) < 2 * h) ++band;
    }
    CHECK(band > count / 2);
    CHECK(grid.listEntries() > 0);
}
} // namespace

TEST_CASE("The distance grid's cell lists give bitwise the tree's closest point", "[SurfaceTool][DistanceGrid]") {
    // coplanar triangles of a notched voxel cube (ties on their shared edges), a tessellated sphere
    // and the probe
    Voxels notched = Voxels::box(Vec3(0, 0, 0), Vec3(0.02, 0.02, 0.02), 2, 2, 2);
    notched.full[7] = 0;
    checkListsAgainstTree(notched.surface(), 24, 20000);
    checkListsAgainstTree(icosphere(4, 0.02, Vec3(0.001, 0.002, 0.003)), 40, 20000);
    const fascia::surface::TriangleSurface probe = fascia::surface::readSurface(std::string(FASCIA_SOURCE_DIR) + "/scenes/meshes/probe.obj");
    checkListsAgainstTree(Mesh{probe.points, probe.triangles}, 64, 20000);
}

TEST_CASE("The distance grid's memory limit counts its cell lists, for any thread count", "[SurfaceTool][DistanceGrid]") {
    const Mesh ball = icosphere(3, 0.02, Vec3::Zero());
    const TriangleTree tree(ball.points, ball.triangles);
    const DistanceGrid full(tree, 24);
    const double nodes = DistanceGrid::bytesFor(full.counts());
    const double total = double(full.bytes() + full.listBytes());
    // 8 bytes a node and one more offset, and 8 bytes an entry
    CHECK(nodes + 4 == total - 8.0 * double(full.listEntries()));
    REQUIRE(full.listEntries() > 1000);
    const int before = omp_get_max_threads();
    for (int threads : {1, 2}) {
        omp_set_num_threads(threads);
        CAPTURE(threads);
        const DistanceGrid exact(tree, 24, total);  // the exact total fits
        CHECK(exact.listEntries() == full.listEntries());
        CHECK_THROWS_AS(DistanceGrid(tree, 24, total - 8), DistanceGrid::TooLarge);  // one entry less does not
        CHECK_THROWS_AS(DistanceGrid(tree, 24, nodes + 3), DistanceGrid::TooLarge);  // nor do the nodes alone
    }
    omp_set_num_threads(before);
}
