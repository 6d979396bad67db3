"""A controller in Python presses a rigid sphere into a soft block and records the force-depth
curve: every step it moves the tool (on_step_begin), then reads the force the block exerts on it
(on_step_end). The block is the quarter model of scenes/interaction/sphere_indent.xml (TLED,
neo-Hookean, E = 3 kPa, nu = 0.4; a sphere of R = 10 mm). Writes force_depth.csv and, with
matplotlib, force_depth.png, and prints the curve against Hertz's F = 4/3 E* sqrt(R) d^1.5 (times 1/4:
a quarter model).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/press_controller.py [OUTPUT_DIR]
"""
import os
import sys

import numpy as np

import fascia


class Press(fascia.Controller):
    """Moves the tool down at `speed` (m/s) from `start` (its centre's height, m) to `depth`, then
    holds it; records (t, depth, force) after every step."""

    def __init__(self, tool="ball", start=0.03, speed=0.004, depth=0.001):
        self.tool_name, self.start, self.speed, self.depth = tool, start, speed, depth
        self.rows = []

    def on_init(self, sim):
        self.tool = sim.tool(self.tool_name)

    def on_step_begin(self, sim, t):
        d = min(self.depth, self.speed * t)
        self.tool.position = [0.0, 0.0, self.start - d]

    def on_step_end(self, sim, t):
        d = self.start - self.tool.position[2]
        self.rows.append((t, d, self.tool.force[2]))


def block(press):
    root = fascia.Node("root", dt="auto", dtSafety=0.5)
    root.add("SphereTool", name="ball", body="@block/state", radius=0.01, keyTimes=[0], keyPositions=[0, 0, 0.03])
    b = root.add_child("block")
    b.add("GridMesh", name="grid", min=[0, 0, 0], max=[0.04, 0.04, 0.02], resolution=[8, 8, 4], element="hexahedra")
    b.add("MechanicalObject", name="state")
    b.add("LumpedMass", density=1000)
    b.add("NeoHookean", name="mat", youngModulus=3000, poissonRatio=0.4)
    b.add("TLEDForceField", name="tled")
    b.add("SemiImplicitEuler", damping=30)
    b.add("FixedConstraint", name="symX", group="xmin", directions=[1, 0, 0])
    b.add("FixedConstraint", name="symY", group="ymin", directions=[0, 1, 0])
    b.add("FixedConstraint", name="base", group="zmin")
    root.add(press, name="press")
    return root


def main(out):
    os.makedirs(out, exist_ok=True)
    press = Press()
    with fascia.Simulation(block(press), output_dir=out) as sim:
        sim.run(time=0.4)
    rows = np.array(press.rows)
    np.savetxt(os.path.join(out, "force_depth.csv"), rows, delimiter=",", header="t,depth,force", comments="")
    E, nu, R = 3000.0, 0.4, 0.01
    hertz = lambda d: 0.25 * 4.0 / 3.0 * E / (1 - nu**2) * np.sqrt(R) * d**1.5  # noqa: E731
    for d in (0.00025, 0.0005, 0.001):
        i = int(np.argmin(np.abs(rows[:, 1] - d)))
        print(f"depth {rows[i, 1] * 1e3:.3f} mm: force {rows[i, 2] * 1e3:.4f} mN (Hertz {hertz(rows[i, 1]) * 1e3:.4f} mN)")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return rows
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot(rows[:, 1] * 1e3, rows[:, 2] * 1e3, label="Fascia (TLED, quarter model)")
    dd = np.linspace(0, 0.001, 50)
    ax.plot(dd * 1e3, hertz(dd) * 1e3, "--", label="Hertz, half-space (quarter)")
    ax.set_xlabel("indentation depth (mm)")
    ax.set_ylabel("force on the sphere (mN)")
    ax.set_title("Python controller: sphere into a block (8x8x4 hexahedra)", fontsize=10)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "force_depth.png"), dpi=100)
    return rows


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/press")
