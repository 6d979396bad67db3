"""Controllers in Python: a class whose hooks run every step (python/src/PyController.h)."""
import ast
import importlib
import importlib.util
import os
import shlex

from ._errors import SceneError


class Controller:
    """Subclass it and define any of the hooks; add an instance to a node (``node.add(MyController())``)
    or name the class in XML (``<PythonController controller="mymodule.MyController" args="depth=0.01"/>``).

    - ``on_init(self, sim)``: after the scene is built, before any step;
    - ``on_step_begin(self, sim, t)``: at the start of each step, before the forces: move tools, write
      external forces or positions;
    - ``on_step_end(self, sim, t)``: after each step: read forces, record data.

    A hook returns None; one that raises stops the run with a fascia.ControllerError whose cause is
    its exception."""


def instantiate(spec, args, scene_file):
    """The controller of an XML PythonController: spec "module.Class" or "file.py:Class" (the file
    relative to the scene's folder), args "key=literal ..."."""
    if ":" in spec:
        path, _, cls = spec.rpartition(":")
        if not os.path.isabs(path) and scene_file and not scene_file.startswith("<"):
            path = os.path.join(os.path.dirname(scene_file), path)
        if not os.path.isfile(path):
            raise SceneError(f"no Python file '{path}'")
        name = "fascia_controller_" + os.path.splitext(os.path.basename(path))[0]
        loader = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(loader)
        loader.loader.exec_module(module)
    else:
        modname, _, cls = spec.rpartition(".")
        if not modname:
            raise SceneError(f"controller '{spec}': write \"module.Class\" or \"file.py:Class\"")
        module = importlib.import_module(modname)
    if not hasattr(module, cls):
        raise SceneError(f"module '{module.__name__}' has no class '{cls}'")
    kwargs = {}
    for word in shlex.split(args or ""):
        key, eq, text = word.partition("=")
        if not eq or not key.isidentifier():
            raise SceneError(f"args: '{word}' is not key=value")
        try:
            kwargs[key] = ast.literal_eval(text)
        except (ValueError, SyntaxError):
            kwargs[key] = text  # a bare word is a string
    return getattr(module, cls)(**kwargs)
