"""fascia.View: a numpy array that views Fascia's memory and refuses to be used once that memory no
longer stands for the state (the simulation closed, the topology changed)."""
import numpy as np

from ._errors import StaleViewError


def _check(a):
    ref = getattr(a, "_fascia_ref", None)
    if ref is not None:
        problem = ref.problem()
        if problem:
            raise StaleViewError(problem)


def _plain(x):
    if isinstance(x, View):
        _check(x)
        return x.view(np.ndarray)
    if isinstance(x, tuple):
        return tuple(_plain(i) for i in x)
    return x


class View(np.ndarray):
    """An (n, 3) float64 array over a state's node array: no copy is made, a write between steps is
    what the next step reads (where the array is writeable: x, v, external_force). Indexing, ufuncs
    and printing raise fascia.StaleViewError once the view is stale; np.asarray(view) gives a plain
    array that no longer checks (its memory stays allocated, never dangling)."""

    _fascia_ref = None

    def __array_finalize__(self, obj):
        self._fascia_ref = getattr(obj, "_fascia_ref", None)

    def __getitem__(self, key):
        _check(self)
        return super().__getitem__(key)

    def __setitem__(self, key, value):
        _check(self)
        super().__setitem__(key, value)

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        if "out" in kwargs:
            kwargs["out"] = _plain(kwargs["out"])
        result = getattr(ufunc, method)(*(_plain(i) for i in inputs), **kwargs)
        return result

    def __array_function__(self, func, types, args, kwargs):
        _check(self)
        args = tuple(_plain(a) for a in args)
        return func(*args, **kwargs)

    def __repr__(self):
        _check(self)
        return "View(" + repr(self.view(np.ndarray)) + ", " + repr(self._fascia_ref.label) + ")"

    def __str__(self):
        _check(self)
        return str(self.view(np.ndarray))

    def __iter__(self):
        _check(self)
        return super().__iter__()

    def __reduce__(self):
        _check(self)
        return np.asarray(self).copy().__reduce__()

    @property
    def valid(self):
        """True while the view stands for the state."""
        return not self._fascia_ref.problem()


def wrap(array):
    """The View of an array made by _fascia (its base is the ViewRef)."""
    v = array.view(View)
    v._fascia_ref = array.base
    return v
