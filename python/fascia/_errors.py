"""Fascia's exceptions. The core's located errors arrive as these (python/src/Errors.cpp)."""


class ErrorRecord:
    """One located error: file, line (None when unknown), message and notes."""

    def __init__(self, file=None, line=None, message="", notes=()):
        self.file, self.line, self.message, self.notes = file, line, message, list(notes)

    def __repr__(self):
        where = f"{self.file}:{self.line}" if self.line else (self.file or "")
        return f"ErrorRecord({where!r}, {self.message!r})"


class FasciaError(Exception):
    """Any error of Fascia. ``file`` and ``line`` locate it (None when nothing does), ``message`` is
    its text without the location, ``notes`` what to do, ``errors`` every error found with it."""

    def __init__(self, text, file=None, line=None, message=None, notes=(), errors=(), **extra):
        super().__init__(text)
        self.file, self.line = file, line
        self.message = text if message is None else message
        self.notes = list(notes)
        self.errors = list(errors) or [ErrorRecord(file, line, self.message, self.notes)]
        for k, v in extra.items():
            setattr(self, k, v)


class SceneError(FasciaError, ValueError):
    """Invalid input: a scene, a mesh, a parameter value (fascia-run's exit code 2)."""


class ParameterError(SceneError, TypeError):
    """A parameter given a value of the wrong type or shape (located at the call that gave it)."""


class SimulationError(FasciaError, RuntimeError):
    """A step failed (NaN, a diverging run): ``step``, ``time`` and ``worst_element`` (a dict of
    force_field, index, J, centroid, or None) say where; ``Simulation.save_last_good_state`` keeps
    the state before it."""

    step = None
    time = None
    worst_element = None


class ControllerError(SimulationError):
    """A Python controller's hook raised (its exception is ``__cause__``, with its traceback) or
    returned something other than None."""


class OutputError(FasciaError, OSError):
    """An output file or folder that cannot be written."""


class StateError(FasciaError, ValueError):
    """A value written into the state that the step cannot take (NaN, infinity, a wrong shape)."""


class StaleViewError(FasciaError, RuntimeError):
    """A view of a simulation that was closed, or of a state whose storage changed."""
