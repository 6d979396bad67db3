"""Scenes built in Python: fascia.Node and the components added to it, with the names and
parameters of the XML (docs/python.md). A scene becomes the same tree of (tag, file, line,
attributes, children) an XML file parses into, so that both run bitwise the same. Parameters are
checked when given, against the registry's declarations, and errors are located at the line of
the user's call."""
import difflib
import os
import sys

import numpy as np

from . import _fascia
from ._errors import ParameterError, SceneError

_HERE = os.path.dirname(os.path.abspath(__file__))
_params_cache = {}
_classes = {}


def caller():
    """(file, line) of the first frame outside the fascia package."""
    f = sys._getframe(1)
    while f is not None and os.path.dirname(os.path.abspath(f.f_code.co_filename)) == _HERE:
        f = f.f_back
    if f is None:
        return ("<python>", 0)
    return (os.path.abspath(f.f_code.co_filename) if not f.f_code.co_filename.startswith("<") else f.f_code.co_filename,
            f.f_lineno)


def params_of(cls):
    """{name: (type, unit, required, output, link, help)} of a registered component ("Node" too)."""
    if cls not in _params_cache:
        _params_cache[cls] = {p[0]: p[1:] for p in _fascia.component_params(cls)}
    return _params_cache[cls]


def located(exc_type, text, loc, **extra):
    file, line = loc
    return exc_type(f"{file}:{line}: error: {text}", file=file, line=line, message=text, **extra)


class LinkRef:
    """A link to a component's parameter, "@/root/body/loader.positions" (``component.positions``)."""

    def __init__(self, component, param):
        self.component, self.param = component, param

    def text(self):
        return "@" + self.component.path + "." + self.param

    def __repr__(self):
        return f"LinkRef({self.text()!r})"


def _numbers(value, what, shape, integer):
    """value as an array of the given shape (None: any length), or a ParameterError text."""
    try:
        a = np.asarray(value)
    except Exception as e:  # noqa: BLE001 (anything numpy cannot take is the user's mistake)
        return None, f"{what}: {e}"
    if a.dtype == object or not (np.issubdtype(a.dtype, np.number) or a.dtype == bool):
        return None, f"{what}: expected numbers, got {type(value).__name__} {_short(value)}"
    if integer and not np.issubdtype(a.dtype, np.integer):
        if not np.all(np.isfinite(a)) or not np.all(a == np.round(a)):
            return None, f"{what}: expected integers, got {_short(value)}"
        a = a.astype(np.int64)
    if shape is not None:
        if a.ndim == 1 and len(shape) == 2 and a.size == 0:
            a = a.reshape(0, shape[1])
        if a.ndim != len(shape) or any(s is not None and s != d for s, d in zip(shape, a.shape)):
            want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ")"
            return None, f"{what}: expected an array of shape {want}, got shape {a.shape}"
    return a, None


def _short(v):
    r = repr(v)
    return r if len(r) < 60 else r[:57] + "..."


def _join(a, integer):
    flat = a.ravel().tolist()
    return " ".join(str(int(x)) for x in flat) if integer else " ".join(repr(float(x)) for x in flat)


_SHAPES = {"vec3": ((3,), False), "index list": ((None,), True), "number list": ((None,), False),
           "positions": ((None, 3), False), "tetrahedra": ((None, 4), True), "hexahedra": ((None, 8), True),
           "triangles": ((None, 3), True)}


def format_value(owner, name, ptype, value):
    """The attribute text of a parameter value, or raises a ParameterError text (a str) back."""
    what = f"{owner} parameter '{name}' [{ptype}]"
    if isinstance(value, Component):
        return "@" + value.path
    if isinstance(value, LinkRef):
        return value.text()
    if isinstance(value, str):
        return value
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if ptype.startswith("link to"):
        raise ValueError(f"{what}: expected a component or \"@path\", got {_short(value)}")
    if ptype == "bool":
        if isinstance(value, (bool, np.bool_)) or value in (0, 1):
            return "true" if value else "false"
        raise ValueError(f"{what}: expected True or False, got {_short(value)}")
    if ptype in ("int", "double", "time step"):
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
            raise ValueError(f"{what}: expected a number, got {type(value).__name__} {_short(value)}")
        if ptype == "int":
            if float(value) != int(value):
                raise ValueError(f"{what}: expected an integer, got {value!r}")
            return str(int(value))
        return repr(float(value))
    if ptype in _SHAPES:
        shape, integer = _SHAPES[ptype]
        if ptype == "index list" and isinstance(value, (int, np.integer)) and not isinstance(value, bool):
            value = [value]
        a, problem = _numbers(value, what, shape, integer)
        if problem:
            raise ValueError(problem)
        return _join(a, integer)
    raise ValueError(f"{what}: cannot be set (an output, or a type Python does not give)")


class _Item:
    """What Node and Component share: a class, a name, parameters as attribute texts, a location."""

    def __init__(self, cls, name, loc):
        self.cls, self.name, self.loc = cls, name, loc
        self._attrs = {}
        self.parent = None

    def set(self, **params):
        """Sets parameters (the XML attribute names); checked at once."""
        self._set(params, caller())
        return self

    def _set(self, params, loc):
        declared = params_of(self.cls)
        for k, v in params.items():
            if k == "name":
                self.name = str(v)
                continue
            if k not in declared:
                close = difflib.get_close_matches(k, list(declared), 1)
                hint = f"; did you mean '{close[0]}'?" if close else ""
                raise located(SceneError, f"{self.cls} has no parameter '{k}'{hint}", loc)
            ptype, _, _, output = declared[k][:4]
            if output:
                raise located(ParameterError, f"{self.cls} parameter '{k}' is an output: link to it "
                                              f"(other.{k}) instead of setting it", loc)
            try:
                self._attrs[k] = format_value(self.cls, k, ptype, v)
            except ValueError as e:
                raise located(ParameterError, str(e), loc) from None

    def attribute(self, name):
        """The attribute text of a parameter set here (None when not set)."""
        return self._attrs.get(name)

    def _tree(self, children):
        attrs = ([("name", self.name)] if self.name is not None else []) + list(self._attrs.items())
        return (self.cls, self.loc[0], self.loc[1], attrs, children)


class Component(_Item):
    """A component added to a Node. ``help()`` on it shows ``fascia-run --describe``; ``comp.p``
    is a link to its parameter p (give it to another component's parameter)."""

    def __init__(self, cls, node, name, loc):
        super().__init__(cls, name, loc)
        self.parent = node
        self.controller_object = None

    @property
    def path(self):
        if self.name is None:  # a link needs a name: give it the one the scene would
            siblings = [c for c in self.parent._items if isinstance(c, Component) and c.cls == self.cls]
            self.name = self.cls if siblings.index(self) == 0 else f"{self.cls}{siblings.index(self)}"
        return self.parent.path + "/" + self.name

    def __getattr__(self, p):
        if p.startswith("_") or p in ("cls", "name", "loc", "parent", "controller_object"):
            raise AttributeError(p)
        if p in params_of(self.cls):
            return LinkRef(self, p)
        raise AttributeError(f"{self.cls} has no parameter '{p}'")

    def tree(self):
        return self._tree([])

    def __repr__(self):
        return f"<{self.cls} {self.name or '(unnamed)'}>"


def component_class(cls):
    """The Python class of a registered component: its docstring is the --describe text."""
    if cls not in _classes:
        _classes[cls] = type(cls, (Component,), {"__doc__": _fascia.describe(cls), "__module__": "fascia.components"})
    return _classes[cls]


class Node(_Item):
    """A node of a scene: ``root = fascia.Node("root", dt="auto")``, ``body = root.add_child("body")``,
    ``body.add("GridMesh", min=[0, 0, 0], max=[.1, .1, .1], resolution=[8, 8, 8])``."""

    def __init__(self, name="root", **params):
        super().__init__("Node", name, caller())
        self._items = []
        self._set(params, self.loc)

    @property
    def path(self):
        return ("" if self.parent is None else self.parent.path) + "/" + self.name

    def add_child(self, name, **params):
        """A child node, with its parameters (dt, gravity ...)."""
        n = Node(name, **params)  # (located at the user's call: caller() skips the package's frames)
        n.parent = self
        self._items.append(n)
        return n

    def add(self, what, name=None, **params):
        """Adds a component: a registered name ("HEMLForceField"), a fascia.Controller object, or a
        fascia.Mesh. Returns it (a Component)."""
        loc = caller()
        from ._controller import Controller
        from ._mesh import Mesh
        if isinstance(what, Mesh):
            params = {**what.params(), **params}
            what = "InlineMesh"
        if isinstance(what, Controller) or (not isinstance(what, str) and _has_hooks(what)):
            obj, what = what, "PythonController"
        else:
            obj = None
        if not isinstance(what, str):
            raise located(ParameterError, f"add() takes a component name, a Controller or a Mesh, not {_short(what)}", loc)
        try:
            cls = component_class(what)
        except SceneError as e:
            raise located(SceneError, e.message, loc) from None
        c = cls(what, self, name, loc)
        c._set(params, loc)
        c.controller_object = obj
        self._items.append(c)
        return c

    def __getitem__(self, name):
        for i in self._items:
            if i.name == name:
                return i
        raise KeyError(f"no child or component '{name}' in node '{self.name}'")

    @property
    def children(self):
        return [i for i in self._items if isinstance(i, Node)]

    @property
    def components(self):
        return [i for i in self._items if isinstance(i, Component)]

    def tree(self, handed=None):
        """The scene tree (the form an XML scene parses into); controller objects are handed over
        to the module (their ids appended to `handed`)."""
        out = []
        for i in self._items:
            if isinstance(i, Node):
                out.append(i.tree(handed))
            elif i.controller_object is not None:
                oid = _fascia.hand_over(i.controller_object)
                if handed is not None:
                    handed.append(oid)
                t = i.tree()
                out.append((t[0], t[1], t[2], t[3] + [("object", str(oid))], []))
            else:
                out.append(i.tree())
        return self._tree(out)

    def __repr__(self):
        return f"<Node {self.path}: {len(self.children)} children, {len(self.components)} components>"


def _has_hooks(obj):
    return any(hasattr(obj, h) for h in ("on_step_begin", "on_step_end", "on_init")) and not isinstance(obj, type)


def override(tree, path, param, value):
    """The tree with one attribute set: path "/root/body/ff" (or "body/ff", from the root), param a
    parameter name. Components are matched by name, then by class when one of a class is unnamed."""
    parts = [p for p in path.strip("/").split("/") if p]
    if parts and parts[0] == dict(tree[3]).get("name", "root") and (len(parts) > 1 or path.startswith("/")):
        parts = parts[1:]
    return _override(tree, parts, param, value, path)


def _override(entry, parts, param, value, path):
    if not parts:
        return _set_attr(entry, param, value, path)
    head = parts[0]
    children = list(entry[4])
    matches = [i for i, c in enumerate(children) if dict(c[3]).get("name") == head]
    if not matches:
        matches = [i for i, c in enumerate(children) if c[0] == head and "name" not in dict(c[3])]
    if len(matches) != 1:
        raise SceneError(f"override '{path}.{param}': no single node or component '{head}' in "
                         f"'{dict(entry[3]).get('name', entry[0])}'")
    i = matches[0]
    children[i] = _override(children[i], parts[1:], param, value, path)
    return (entry[0], entry[1], entry[2], entry[3], children)


def _set_attr(entry, param, value, path):
    declared = params_of(entry[0])
    if param not in declared:
        close = difflib.get_close_matches(param, list(declared), 1)
        raise SceneError(f"override '{path}.{param}': {entry[0]} has no parameter '{param}'"
                         + (f"; did you mean '{close[0]}'?" if close else ""))
    try:
        text = format_value(entry[0], param, declared[param][0], value)
    except ValueError as e:
        raise ParameterError(f"override '{path}.{param}': {e}") from None
    attrs = [(k, v) for k, v in entry[3] if k != param] + [(param, text)]
    return (entry[0], entry[1], entry[2], attrs, list(entry[4]))


def apply_overrides(tree, overrides):
    """overrides: {"path.param": value} or {(path, param): value}."""
    for key, value in (overrides or {}).items():
        if isinstance(key, tuple):
            path, param = key
        else:
            path, _, param = str(key).rpartition(".")
            if not path:
                raise SceneError(f"override '{key}': write 'path/to/component.parameter'")
        tree = override(tree, path, param, value)
    return tree
