"""A parameter sweep on Dask: the cube of build_scene.py over Young's modulus and Poisson's ratio
(through the law's parameters: mu = E / (2 (1 + nu)), lambda = E nu / ((1 + nu)(1 - 2 nu))), 2
workers on a LocalCluster of this machine. Each run reports the top's reaction force at 0.2 s.

    PYTHONPATH=build/python:examples/python /usr/bin/python3 examples/python/sweep_moduli.py
"""
import sys

import fascia

from build_scene import cube


def lame(E, nu):
    return {"body/law.mu": E / (2 * (1 + nu)), "body/law.C1": E / (4 * (1 + nu)),
            "body/law.lambda": E * nu / ((1 + nu) * (1 - 2 * nu))}


def push_force(sim):
    """The z reaction on the pushed (top) face at the end (N): the force holding it 5 mm down."""
    st = sim.state("state")
    top = st.x0[:, 2] > 0.1 - 1e-9
    return float(st.reaction[top, 2].sum())


def main(out=None, workers=2):
    sets = [dict(E=E, nu=nu, **lame(E, nu)) for E in (20e3, 40e3) for nu in (0.3, 0.45)]
    table = fascia.sweep(lambda: cube(4), [{k: v for k, v in s.items() if "/" in k} for s in sets],
                         outputs=[push_force, "time"], time=0.2, n_workers=workers, output_dir=out)
    table["E"] = [s["E"] for s in sets]
    table["nu"] = [s["nu"] for s in sets]
    print(table[["E", "nu", "push_force", "time", "error", "wall_s"]].to_string())
    return table


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
