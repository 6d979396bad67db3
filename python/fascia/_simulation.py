"""fascia.Simulation: load, step, read and write a scene from Python (docs/python.md)."""
import os

import numpy as np

from . import _fascia
from ._errors import ParameterError, StateError
from ._scene import Node, apply_overrides, caller
from ._views import wrap

_WRITEABLE = ("x", "v", "external_force")
_ARRAYS = ("x", "v", "f", "x0", "reaction", "external_force")


class State:
    """A mechanical state's node arrays as (n, 3) float64 views of Fascia's memory: x, v and
    external_force writeable between steps; f, x0 and reaction read-only. Assigning
    (``state.x = a``) copies a into the state, checked for shape and finiteness."""

    def __init__(self, sim, name):
        self._sim, self.name = sim, name
        self._views = {}

    def _view(self, which):
        v = self._views.get(which)
        if v is None or not v.valid:
            v = wrap(self._sim._core.view(self.name, which))
            self._views[which] = v
        return v

    def __len__(self):
        return self._sim._core.state_size(self.name)

    def _assign(self, which, value):
        target = self._view(which)
        a = np.asarray(value)
        if a.dtype == object or not np.issubdtype(a.dtype, np.number):
            raise ParameterError(f"state '{self.name}'.{which}: expected numbers, got dtype {a.dtype}")
        if a.shape not in (target.shape, (3,), ()):
            raise ParameterError(f"state '{self.name}'.{which}: expected shape {target.shape}, got {a.shape}")
        if not np.all(np.isfinite(a)):
            raise StateError(f"state '{self.name}'.{which}: the values must be finite (no NaN or infinity)")
        target[...] = a


def _array_property(which):
    doc = f"the state's {which} as a view ({'writeable' if which in _WRITEABLE else 'read-only'})"
    if which in _WRITEABLE:
        return property(lambda self: self._view(which), lambda self, v: self._assign(which, v), doc=doc)
    return property(lambda self: self._view(which), doc=doc)


for _a in _ARRAYS:
    setattr(State, _a, _array_property(_a))
State.rest_positions = State.x0


class Tool:
    """A rigid tool: its pose (position, orientation as a quaternion w, x, y, z) and velocity are set
    between steps (a velocity moves it every step), its force and torque read after them."""

    def __init__(self, sim, name):
        self._sim, self.name = sim, name

    def _get(self, key):
        return self._sim._core.tool(self.name)[key]

    position = property(lambda s: s._get("position"), lambda s, p: s._sim._core.set_tool_pose(s.name, position=p))
    orientation = property(lambda s: s._get("orientation"),
                           lambda s, q: s._sim._core.set_tool_pose(s.name, orientation=q))
    force = property(lambda s: s._get("force"), doc="the force the body exerts on the tool at the last step (N)")
    torque = property(lambda s: s._get("torque"), doc="its torque about the tool's position (N m)")

    def set_pose(self, position=None, orientation=None):
        self._sim._core.set_tool_pose(self.name, position, orientation)

    def set_velocity(self, velocity=None, angular_velocity=None):
        """Moves the tool every step by dt * velocity (m/s) and turns it by dt * angular_velocity (rad/s)."""
        self._sim._core.set_tool_velocity(self.name, velocity, angular_velocity)

    @property
    def velocity(self):
        return self._sim._core.tool(self.name).get("velocity", np.zeros(3))

    @velocity.setter
    def velocity(self, v):
        self.set_velocity(velocity=v)


def _tree_of(scene, handed):
    if isinstance(scene, Node):
        return scene.tree(handed), ""
    if isinstance(scene, tuple):
        return scene, ""
    path = os.fspath(scene)
    return _fascia.parse_file(path), path


class Simulation:
    """One simulation of a scene: a fascia.Node, or an XML file's path (fascia.load).

    output_dir: folder the exporters and monitors write into (default: the current one); dt: a time
    step overriding the scene's; overrides: {"path/to/component.parameter": value} applied before
    the build; threads: OpenMP threads (results do not depend on them)."""

    def __init__(self, scene, output_dir=None, dt=None, overrides=None, threads=None, _tree=None):
        if threads is not None:
            _fascia.set_threads(int(threads))
        handed = []
        try:
            tree, scene_file = _tree if _tree is not None else _tree_of(scene, handed)
            tree = apply_overrides(tree, overrides)
            self._core = _fascia.Core(tree, scene_file, os.fspath(output_dir) if output_dir else "",
                                      float(dt) if dt else 0.0)
        finally:
            for h in handed:
                _fascia.drop_hand_over(h)
        self._states, self._tools = {}, {}
        import weakref
        self._core.attach(weakref.ref(self))

    # ---- time
    time = property(lambda self: self._core.time, doc="simulated time (s)")
    step_count = property(lambda self: self._core.step_count, doc="steps done")
    dt = property(lambda self: self._core.dt, lambda self, v: setattr(self._core, "dt", float(v)), doc="time step (s)")
    critical_dt = property(lambda self: self._core.critical_dt, doc="the smallest stable step of the force fields (s)")
    output_dir = property(lambda self: self._core.output_dir)
    closed = property(lambda self: self._core.closed)

    def step(self):
        """One step of dt (the GIL released while it runs)."""
        self._core.run(1)

    def run(self, steps=None, time=None, progress=False):
        """Runs `steps` steps, or up to the simulated time `time` exactly (the last step shortened);
        progress=True shows a tqdm bar (terminal or notebook)."""
        if (steps is None) == (time is None):
            raise ParameterError("run() takes steps=N or time=T (one of them)")
        if time is not None:
            return self.run_until(time, progress)
        if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)):
            raise ParameterError(f"run(): steps must be an integer, not {steps!r}")
        steps = int(steps)
        if steps < 0:
            raise ParameterError(f"run(): steps must be >= 0, not {steps}")
        if not progress:
            self._core.run(steps)
            return
        bar = _bar(steps, progress)
        chunk = max(1, steps // 200)
        try:
            done = 0
            while done < steps:
                n = min(chunk, steps - done)
                self._core.run(n)
                done += n
                bar.update(n)
        finally:
            bar.close()

    def run_until(self, T, progress=False):
        """Runs to the simulated time T exactly."""
        T = float(T)
        if not progress:
            self._core.run_until(T)
            return
        total = self._core.steps_until(T)
        bar = _bar(total, progress)
        try:
            chunk = max(1, total // 200)
            while True:
                n = self._core.step_toward(T, chunk)
                bar.update(n)
                if n == 0:
                    break
        finally:
            bar.close()

    # ---- state
    def state(self, name):
        """A mechanical state by name or path: its node arrays as views (fascia.State)."""
        if name not in self._states:
            self._core.state_size(name)  # (raises when there is none)
            self._states[name] = State(self, name)
        return self._states[name]

    def tool(self, name):
        """A rigid tool by name or path (fascia.Tool)."""
        if name not in self._tools:
            self._core.tool(name)
            self._tools[name] = Tool(self, name)
        return self._tools[name]

    def surface(self, name):
        """(points, triangles) of a body's boundary or a visual surface: points a read-only view."""
        points, triangles = self._core.surface(name)
        return wrap(points), triangles

    def cell_data(self, force_field):
        """The force field's per-element fields at the current state ({"J": ..., "vonMises": ...}), copies."""
        return self._core.cell_data(force_field)

    def elements(self, force_field):
        """(tetrahedra, hexahedra) of an element force field, as int arrays (copies)."""
        return self._core.elements(force_field)

    def components(self):
        """[(path, class)] of every node and component."""
        return self._core.components()

    def param(self, path, name):
        """A parameter's value as the scene would write it (outputs too: "@loader.positions")."""
        return self._core.param(path, name)

    def monitor(self, name):
        """A Monitor's CSV so far, as a pandas DataFrame."""
        import pandas
        path = self._core.param(name, "filename") or name + ".csv"
        return pandas.read_csv(os.path.join(self.output_dir or ".", path), comment="#")

    # ---- checkpoints
    def save(self, path):
        self._core.save(os.fspath(path))

    def restore(self, path):
        self._core.restore(os.fspath(path))

    def save_last_good_state(self, path):
        """After a failed step: writes the state before it as a checkpoint; returns its step (-1: none)."""
        return self._core.save_last_good_state(os.fspath(path))

    snapshot_every = property(None, lambda self, n: self._core.set_snapshot_every(int(n)),
                              doc="steps between the divergence check's snapshots (1: before every step)")

    def timers(self):
        """[(path, type, seconds, calls)] per component (fascia.set_timers(True) first)."""
        return self._core.timers()

    # ---- end
    def close(self):
        """Records the final state and closes the files; views then raise fascia.StaleViewError."""
        self._core.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        return f"<fascia.Simulation t={self._core.time:g} s, {self._core.step_count} steps>"


def _bar(total, progress):
    if progress == "notebook":
        from tqdm.notebook import tqdm
    else:
        from tqdm.auto import tqdm
    return tqdm(total=total, unit="step")


def load(path, **kwargs):
    """A Simulation of an XML scene file (output_dir=, dt=, overrides=, threads=)."""
    return Simulation(path, **kwargs)


def loads(xml, name="<string>", base_dir=".", **kwargs):
    """A Simulation of an XML string; relative paths are relative to base_dir."""
    return Simulation(None, _tree=(_fascia.parse_string(xml, name, os.fspath(base_dir)), ""), **kwargs)
