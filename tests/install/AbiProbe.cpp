// fascia-abi-probe SCENE, built with pkg-config alone by tests/install/examples_from_install.sh:
// the values a program hands to the library come back as it gave them, and the library's results
// are sane, across the boundary of libfascia_core. Built for another
// instruction set than the library, this crashed in BaseTool::pose() before Eigen's alignment was
// fixed for every user (fascia/base/Abi.h): the library stored the returned Pose with 32-byte
// aligned moves into the caller's 16-byte aligned slot. Exit code 0 when every check holds.
#include "fascia/sim/Simulation.h"
#include "fascia/sim/Tool.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <exception>

namespace {

int failures = 0;
void expect(bool ok, const char* what) {
    std::printf("%-64s %s\n", what, ok ? "ok" : "FAIL");
    failures += ok ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: fascia-abi-probe SCENE.xml (a scene with a tool 'probe' and a state 'state')\n");
        return 1;
    }
    try {
        auto sim = fascia::core::Simulation::fromFile(argv[1]);
        fascia::core::BaseTool& tool = sim->tool("probe");
        const fascia::core::Pose start = tool.pose();
        expect(start.position.allFinite() && std::abs(start.orientation.norm() - 1) < 1e-12, "the scene's pose reads back finite, a unit quaternion");

        // a pose with a rotation, 4 mm into the body: set, then read back
        fascia::core::Pose pressed{start.position - fascia::Vec3(0, 0, 0.004),
                                   Eigen::Quaterniond(Eigen::AngleAxisd(0.3, fascia::Vec3(1, 2, 3).normalized()))};
        tool.setPose(pressed);
        const fascia::core::Pose back = tool.pose();
        // (the position bit for bit; the orientation is normalised by setPose, to round-off)
        expect(back.position == pressed.position && (back.orientation.coeffs() - pressed.orientation.coeffs()).norm() < 1e-14,
               "setPose then pose(): the same position and orientation");

        // Eigen vectors in the library's containers: written here, read there, and back
        auto& state = sim->state("state");
        const fascia::Vec3 push(0.25, -0.5, 1.0);
        state.externalForce()[0] = push;
        expect(state.externalForce()[0] == push, "a force written into the state reads back");
        for (int i = 0; i < 20; ++i) sim->step();
        const fascia::Vec3 f = tool.force();
        expect(f.allFinite() && f.z() > 0, "the pressed tool feels the body push it up (force z > 0)");
        bool finite = true;
        for (const fascia::Vec3& x : state.x()) finite = finite && x.allFinite();
        expect(finite && state.x().size() > 100, "every position the library computed is finite");
        std::printf("tool force after 20 steps: %.6g %.6g %.6g N\n", f.x(), f.y(), f.z());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    return failures == 0 ? 0 : 1;
}
