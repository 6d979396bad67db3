#!/usr/bin/python3
"""What the Python module costs, measured side by side (docs/performance.md, section "Python"):

  1. stepping the abdomen scene 2,000 steps from Python (sim.run) against fascia-run on the same
     scene, alternating, `--rounds` times each (the wall time of the steps alone, as fascia-run's
     summary line reports it);
  2. a Python controller that writes one node's external force every step: the time per step it adds;
  3. reading state.x for 1k and for 1M nodes (a view, not a copy);
  4. a sweep of 16 runs of a 20k-element scene on a LocalCluster of 2 workers against the same 16
     runs one after the other in this process.

  PYTHONPATH=build/python /usr/bin/python3 tools/bench-python.py [--build build] [--rounds 3] [--skip-sweep]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import time
import timeit

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)


def fascia_run_wall(exe, scene, steps, threads):
    out = subprocess.run([exe, scene, "--steps", str(steps), "--quiet", "--threads", str(threads), "--output",
                          "/tmp/fascia-bench-python"], check=True, capture_output=True, text=True).stdout
    return float(re.search(r"([0-9.]+) s wall", out).group(1))


def python_wall(fascia, scene, steps, controller=None):
    if controller is None:
        sim = fascia.load(scene, output_dir="/tmp/fascia-bench-python")
    else:  # the XML scene's tree with a PythonController appended to the root, holding the object
        root = fascia._fascia.parse_file(scene)
        oid = fascia._fascia.hand_over(controller)
        tree = root[:4] + (list(root[4]) + [("PythonController", scene, 0, [("name", "ctl"), ("object", str(oid))], [])],)
        sim = fascia.Simulation(None, output_dir="/tmp/fascia-bench-python", _tree=(tree, scene))
    sim._core.start()
    t = time.perf_counter()
    sim.run(steps=steps)
    wall = time.perf_counter() - t
    sim.close()
    return wall


class TouchOne:
    def __init__(self):
        self.ext = None

    def on_init(self, sim):
        self.ext = sim.state("state").external_force

    def on_step_begin(self, sim, t):
        self.ext[1, 2] = -0.01 * t


def view_cost(fascia, n_per_side):
    root = fascia.Node("root", dt=1e-3)
    b = root.add_child("b")
    b.add("GridMesh", resolution=[n_per_side - 1] * 3, element="hexahedra")
    b.add("MechanicalObject", name="state")
    sim = fascia.Simulation(root)
    st = sim.state("state")
    n = len(st)
    per = min(timeit.repeat(lambda: st.x, number=2000, repeat=5)) / 2000
    per_slice = min(timeit.repeat(lambda: st.x[0], number=2000, repeat=5)) / 2000
    return n, per, per_slice


def sweep_scaling(fascia, runs, steps):
    sys.path.insert(0, os.path.join(SOURCE, "examples", "python"))
    from build_scene import cube  # 15 x 15 x 15 cells x 6 = 20,250 tetrahedra
    sets = [{"body/law.mu": 8000 + 200 * i} for i in range(runs)]
    t = time.perf_counter()
    for s in sets:
        with fascia.Simulation(cube(15), overrides=s, threads=1, output_dir="/tmp/fascia-bench-python") as sim:
            sim.run(steps=steps)
    serial = time.perf_counter() - t
    from distributed import Client, LocalCluster
    os.environ["PYTHONPATH"] = os.pathsep.join([os.path.join(SOURCE, "examples", "python"), os.environ.get("PYTHONPATH", "")])
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        client.submit(lambda: 1).result()  # the workers are up: the cluster's start is not timed
        t = time.perf_counter()
        table = fascia.sweep(lambda: cube(15), sets, outputs=["step_count"], steps=steps, client=client,
                             output_dir="/tmp/fascia-bench-python/sweep")
        parallel = time.perf_counter() - t
    assert table["error"].isna().all(), table["error"].tolist()
    return serial, parallel


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(SOURCE, "build"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--skip-sweep", action="store_true")
    a = ap.parse_args()
    sys.path.insert(0, os.path.join(a.build, "python"))
    import fascia
    fascia.set_threads(a.threads)
    scene = os.path.join(SOURCE, "scenes", "heml", "abdomen.xml")
    exe = os.path.join(a.build, "bin", "fascia-run")
    cli, py, ctl = [], [], []
    for _ in range(a.rounds):  # alternating, so that a neighbour's load falls on all three alike
        cli.append(fascia_run_wall(exe, scene, a.steps, a.threads))
        py.append(python_wall(fascia, scene, a.steps))
        ctl.append(python_wall(fascia, scene, a.steps, TouchOne()))
    m = {k: statistics.median(v) for k, v in (("cli", cli), ("py", py), ("ctl", ctl))}
    print(f"abdomen, {a.steps} steps, {a.threads} threads, median of {a.rounds} alternating rounds:")
    print(f"  fascia-run        {m['cli']:.3f} s  ({1e3 * m['cli'] / a.steps:.4f} ms/step)  rounds {cli}")
    print(f"  Python sim.run    {m['py']:.3f} s  ratio to fascia-run {m['py'] / m['cli']:.3f}  rounds {py}")
    print(f"  + controller      {m['ctl']:.3f} s  adds {1e6 * (m['ctl'] - m['py']) / a.steps:.2f} us/step  rounds {ctl}")
    for side in (10, 100):
        n, per, per_slice = view_cost(fascia, side)
        print(f"  state.x with {n:>8} nodes: {1e6 * per:.2f} us   state.x[0]: {1e6 * per_slice:.2f} us")
    if not a.skip_sweep:
        serial, parallel = sweep_scaling(fascia, 16, 1500)
        print(f"  sweep of 16 runs (20,250 tetrahedra, 1500 steps, 1 thread each): serial {serial:.2f} s, 2 workers {parallel:.2f} s, "
              f"ratio {parallel / serial:.3f}")


if __name__ == "__main__":
    main()
