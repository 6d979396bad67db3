"""A scene built in Python: the cube of examples/python/cube.xml, written with fascia.Node, run for
0.2 s, its top's reaction force printed. Same names and parameters as the XML.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/build_scene.py [OUTPUT_DIR]
"""
import sys

import fascia


def cube(resolution=6):
    """The cube scene (a function, so that a sweep's workers can build it too)."""
    root = fascia.Node("root", dt="auto", endTime=0.2)
    body = root.add_child("body")
    body.add("GridMesh", name="grid", min=[0, 0, 0], max=[0.1, 0.1, 0.1], resolution=[resolution] * 3)
    body.add("MechanicalObject", name="state")
    body.add("LumpedMass", density=1000)
    body.add("CompressibleNeoHookean", name="law", C1=5000, mu=10000, **{"lambda": 90000})
    body.add("HEMLForceField", name="heml")
    body.add("SemiImplicitEuler", damping=20)
    body.add("FixedConstraint", name="base", group="zmin")
    push = body.add("PrescribedDisplacement", name="push", group="zmax", displacement=[0, 0, -0.005],
                    shape="smooth", rampTime=0.1)
    body.add("Monitor", name="probe", reactionOf=push, every=10)
    return root


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "out/cube_python"
    with fascia.Simulation(cube(), output_dir=out) as sim:
        sim.run(time=0.2, progress=sys.stderr.isatty())
        force = sim.state("state").reaction.sum(axis=0)
        print(f"t = {sim.time:.3f} s after {sim.step_count} steps; reaction on the body: {force} N")
        print(sim.monitor("probe").tail(3).to_string())
