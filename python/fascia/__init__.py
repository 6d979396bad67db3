"""Fascia from Python: scenes in XML or Python, stepping, numpy views of the state, controllers,
meshes, and parameter sweeps on Dask (docs/python.md).

    import fascia
    sim = fascia.load("scenes/heml/abdomen.xml")
    organ = sim.state("state")
    sim.run(steps=100)
    print(organ.x[1])
"""
from . import _fascia
from ._controller import Controller
from ._errors import (ControllerError, FasciaError, OutputError, ParameterError, SceneError, SimulationError,
                      StaleViewError, StateError)
from ._mesh import Mesh, read_mesh, write_mesh
from ._scene import Component, LinkRef, Node
from ._simulation import Simulation, State, Tool, load, loads
from ._views import View

set_threads = _fascia.set_threads
threads = _fascia.threads
set_timers = _fascia.set_timers
load_plugin = _fascia.load_plugin


def describe(name):
    """What `fascia-run --describe NAME` prints: the component's parameters."""
    return _fascia.describe(name)


def components():
    """{name: (plugin, summary)} of every registered component."""
    return _fascia.components()


class _Components:
    """fascia.components_.HEMLForceField: the Python class of a component (help() shows its parameters)."""

    def __getattr__(self, name):
        from ._scene import component_class
        if name.startswith("_"):
            raise AttributeError(name)
        return component_class(name)

    def __dir__(self):
        return sorted(_fascia.components())


classes = _Components()


def sweep(*args, **kwargs):
    """Runs one simulation per parameter set on Dask (fascia._sweep.sweep)."""
    from ._sweep import sweep as run
    return run(*args, **kwargs)


__all__ = ["Controller", "ControllerError", "Component", "FasciaError", "LinkRef", "Mesh", "Node", "OutputError",
           "ParameterError", "SceneError", "Simulation", "SimulationError", "StaleViewError", "State", "StateError",
           "Tool", "View", "classes", "components", "describe", "load", "load_plugin", "loads", "read_mesh",
           "set_threads", "set_timers", "sweep", "threads", "write_mesh"]
