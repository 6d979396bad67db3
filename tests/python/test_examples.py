"""Every example of examples/python runs (each in its own process, as a user runs it)."""
import os
import subprocess
import sys

import pytest

from conftest import EXAMPLES


def _run(script, *args):
    env = dict(os.environ)
    import fascia  # the examples import the same module as the tests
    package = os.path.dirname(os.path.dirname(os.path.abspath(fascia.__file__)))
    env["PYTHONPATH"] = os.pathsep.join([package, EXAMPLES])
    return subprocess.run([sys.executable, os.path.join(EXAMPLES, script), *args], env=env, capture_output=True,
                          text=True, timeout=300)


def test_build_scene(tmp_path):
    r = _run("build_scene.py", str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert "t = 0.200 s" in r.stdout and (tmp_path / "probe.csv").exists()


def test_press_controller(tmp_path):
    r = _run("press_controller.py", str(tmp_path))
    assert r.returncode == 0, r.stderr
    rows = (tmp_path / "force_depth.csv").read_text().splitlines()
    assert rows[0] == "t,depth,force" and len(rows) > 100
    last = [float(v) for v in rows[-1].split(",")]
    assert last[1] == pytest.approx(0.001) and last[2] > 0.002  # 1 mm deep, some 3 mN
    assert (tmp_path / "force_depth.png").stat().st_size > 10000


def test_sweep_moduli(tmp_path):
    r = _run("sweep_moduli.py", str(tmp_path))
    assert r.returncode == 0, r.stderr
    lines = [line for line in r.stdout.splitlines() if "None" in line]
    assert len(lines) == 4
    force = [float(line.split()[3]) for line in lines]
    # stiffer (E = 40 kPa) needs more force than E = 20 kPa at the same nu
    assert abs(force[2]) > abs(force[0]) and abs(force[3]) > abs(force[1])
