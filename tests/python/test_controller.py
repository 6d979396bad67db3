"""Controllers in Python, tools from Python, failures that lose nothing."""
import os
import textwrap

import numpy as np
import pytest

import fascia
from build_scene import cube


class Recorder(fascia.Controller):
    def __init__(self):
        self.begin, self.end = [], []

    def on_init(self, sim):
        self.state = sim.state("state")

    def on_step_begin(self, sim, t):
        self.begin.append(t)

    def on_step_end(self, sim, t):
        self.end.append((t, float(self.state.x[-1, 2])))


def test_controller_hooks_run_every_step():
    root = cube(3)
    rec = Recorder()
    root.add(rec, name="rec")
    sim = fascia.Simulation(root)
    sim.run(steps=10)
    assert len(rec.begin) == 10 and len(rec.end) == 10
    assert rec.begin[0] == 0.0 and rec.end[-1][0] == pytest.approx(sim.time)
    assert rec.end[-1][1] < rec.end[0][1] + 1e-12  # the top goes down


class Raises(fascia.Controller):
    def on_step_end(self, sim, t):
        if sim.step_count >= 25:
            raise KeyError("sensor 3 unplugged")


def test_a_controller_that_raises_stops_the_run_and_files_are_complete(tmp_path):
    root = cube(3)
    root["body"].add("VTKExporter", name="out", every=10)
    root.add(Raises(), name="bad")
    sim = fascia.Simulation(root, output_dir=tmp_path)
    with pytest.raises(fascia.ControllerError) as e:
        sim.run(steps=100)
    assert isinstance(e.value.__cause__, KeyError)
    assert "sensor 3 unplugged" in str(e.value) and "on_step_end raised KeyError" in str(e.value)
    frames = [f.co_name for f in _frames(e.value.__cause__.__traceback__)]
    assert "on_step_end" in frames  # the controller's own traceback
    assert sim.step_count == 25 or sim.failed_step == 25
    sim.close()
    csv = (tmp_path / "probe.csv").read_text().splitlines()
    assert len(csv) >= 3 and all(line.count(",") == csv[0].count(",") for line in csv)
    pvd = (tmp_path / "out.pvd").read_text()
    assert pvd.rstrip().endswith("</VTKFile>")
    for name in __import__("re").findall(r'file="([^"]+)"', pvd):
        assert (tmp_path / name).stat().st_size > 0


def _frames(tb):
    while tb is not None:
        yield tb.tb_frame.f_code
        tb = tb.tb_next


class Garbage(fascia.Controller):
    def on_step_begin(self, sim, t):
        return 42


def test_a_controller_that_returns_garbage():
    root = cube(2)
    root.add(Garbage(), name="g")
    sim = fascia.Simulation(root)
    with pytest.raises(fascia.ControllerError, match="on_step_begin returned 42"):
        sim.step()


class WritesNaN(fascia.Controller):
    def on_step_begin(self, sim, t):
        sim.state("state").external_force[0, 0] = float("nan")


def test_a_controller_that_writes_nan():
    root = cube(2)
    root.add(WritesNaN(), name="w")
    with pytest.raises(fascia.ControllerError, match=r"external_force\[0, 0\]"):
        fascia.Simulation(root).step()


def test_controller_named_in_xml(tmp_path):
    (tmp_path / "ctl.py").write_text(textwrap.dedent("""
        class Push:
            def __init__(self, force=1.0, node=0):
                self.force, self.node, self.calls = force, node, 0
            def on_step_begin(self, sim, t):
                sim.state("state").external_force[self.node] = [0, 0, self.force]
                self.calls += 1
        """))
    xml = open(os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python", "cube.xml")).read()
    xml = xml.replace("</Node>\n</Node>", '</Node>\n  <PythonController name="push" controller="ctl.py:Push" '
                      'args="force=0.5 node=3"/>\n</Node>')
    (tmp_path / "scene.xml").write_text(xml)
    sim = fascia.load(tmp_path / "scene.xml")
    sim.run(steps=4)
    assert np.array_equal(sim.state("state").external_force[3], [0, 0, 0.5])
    bad = xml.replace("ctl.py:Push", "ctl.py:Nope")
    (tmp_path / "bad.xml").write_text(bad)
    with pytest.raises(fascia.SceneError, match="has no class 'Nope'") as e:
        fascia.load(tmp_path / "bad.xml")
    assert e.value.line is not None


def test_tools_are_scriptable():
    from press_controller import Press, block
    press = Press(depth=0.0005)
    sim = fascia.Simulation(block(press))
    sim.run(time=0.2)
    ball = sim.tool("ball")
    assert ball.position[2] == pytest.approx(0.03 - 0.0005)
    assert ball.force[2] > 0  # the block pushes the sphere up
    forces = np.array(press.rows)[:, 2]
    assert forces[-1] > forces[len(forces) // 4] > 0
    with pytest.raises(fascia.SceneError, match="quaternion"):
        ball.orientation = [1, 2]
    with pytest.raises(fascia.SceneError, match="no tool|no rigid tool|tool"):
        sim.tool("nothing")


def test_a_tool_velocity_moves_it_every_step():
    from press_controller import block

    class Idle(fascia.Controller):
        def on_step_end(self, sim, t):
            pass

    sim = fascia.Simulation(block(Idle()))
    ball = sim.tool("ball")
    ball.set_pose(position=[0, 0, 0.031])
    ball.velocity = [0, 0, -0.01]
    sim.run(steps=10)
    assert ball.position[2] == pytest.approx(0.031 - 10 * sim.dt * 0.01, abs=1e-12)
    assert np.array_equal(ball.velocity, [0, 0, -0.01])
