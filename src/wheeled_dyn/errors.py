r"""One exception tree for the whole toolkit.

Every error a user can cause (a bad file, an unknown name, a non-physical number) is raised as a
subclass of :class:`WheeledDynError`. Each carries the data needed to act on it as attributes
(``path``, ``line``, ``name``, ``valid`` ...) and a message that names the place and what was
expected. Nothing in the package uses ``assert`` for input validation.

Every error survives a pickle round trip with its data (it is rebuilt from the arguments it was
made with; an argument that cannot be pickled, such as a mapping proxy or a function, travels
as its ``repr``), so an error raised in a worker process reaches the user as the same one-line
message.

Things worth knowing that are not errors (a mesh the dynamics do not need is missing, the disk
cache cannot be used) are :class:`WheeledDynWarning`\ s; the command line prints each as one
line.
"""

from __future__ import annotations

import pickle
from collections.abc import Iterable
from pathlib import Path
from typing import Any


def _names(valid: Iterable[str] | None) -> str:
    if valid is None:
        return ""
    items = sorted(str(v) for v in valid)
    return f"; valid: {', '.join(items)}" if items else "; there are none"


def _rebuild(cls: type, args: tuple, kwargs: dict[str, Any],
             shown: tuple | None = None) -> WheeledDynError:
    r"""``cls(*args, **kwargs)``, its message the one the original had (``shown``)."""
    err = cls(*args, **kwargs)
    if shown is not None:
        err.args = shown
    return err


def _picklable(value: object) -> bool:
    try:
        pickle.dumps(value)
    except Exception:
        return False
    return True


def _restore(cls: type, args: tuple) -> WheeledDynError:
    r"""An error of ``cls`` with ``args``, its constructor not called (its attributes follow
    as the pickle's state)."""
    self: WheeledDynError = Exception.__new__(cls)
    self.args = args
    return self


class WheeledDynError(Exception):
    """Base class of every error raised by wheeled_dyn on purpose.

    The arguments a subclass is constructed with are kept (``__new__`` records them), and
    :meth:`__reduce__` rebuilds the error from them: ``pickle`` (and so a process pool) gives
    back an equal error, message and attributes included, whatever the subclass's signature.
    """

    _ctor: tuple[tuple, dict[str, Any]]

    def __new__(cls, *args: Any, **kwargs: Any) -> WheeledDynError:
        self = super().__new__(cls, *args)
        self._ctor = (args, kwargs)
        return self

    def __reduce__(self):
        ctor = getattr(self, "_ctor", None)
        state = dict(self.__dict__)
        if ctor is not None and _picklable((ctor, state, self.args)):
            return _rebuild, (type(self), *ctor, self.args), state
        # an argument that does not pickle (a mapping proxy, a function): the message and
        # the attributes as they are, each that does not pickle as its repr
        state = {k: v if _picklable(v) else repr(v) for k, v in state.items()
                 if k != "_ctor"}
        return _restore, (type(self), tuple(a if _picklable(a) else str(a)
                                            for a in self.args)), state


class InputFileError(WheeledDynError):
    """A file is missing, unreadable or malformed.

    Attributes: ``path``, ``line`` and ``column`` (1-based, or None), ``reason``.
    """

    def __init__(self, path: str | Path, reason: str, line: int | None = None,
                 column: int | None = None) -> None:
        self.path = Path(path)
        self.line = line
        self.column = column
        self.reason = reason
        where = str(self.path)
        if line is not None:
            where += f":{line}"
            if column is not None:
                where += f":{column}"
        super().__init__(f"{where}: {reason}")


class UnknownNameError(WheeledDynError, KeyError):
    """A name (link, joint, wheel, model, coordinate set, symbol, parameter) does not exist.

    Attributes: ``kind`` (what sort of name), ``name``, ``valid`` (the names that exist),
    ``where`` (file or object the lookup was made in, or None).
    """

    def __init__(self, kind: str, name: str, valid: Iterable[str] | None = None,
                 where: str | None = None) -> None:
        self.kind = kind
        self.name = name
        self.valid = tuple(sorted(str(v) for v in valid)) if valid is not None else None
        self.where = where
        prefix = f"{where}: " if where else ""
        super().__init__(f"{prefix}unknown {kind} {name!r}{_names(valid)}")

    def __str__(self) -> str:  # KeyError would quote the message otherwise
        return self.args[0]


class ModelError(WheeledDynError):
    """A model cannot be built as asked (e.g. a wheel without a radius, a wheel axle that is
    not horizontal). Attributes: ``model``, ``item`` (the link or joint concerned), ``reason``."""

    def __init__(self, model: str, item: str | None, reason: str) -> None:
        self.model = model
        self.item = item
        self.reason = reason
        at = f" ({item})" if item else ""
        super().__init__(f"model {model}{at}: {reason}")


class InertiaError(ModelError):
    """A link's URDF inertia that is not a mass distribution's (not positive semi-definite,
    principal moments against the triangle inequality): a model file may accept it as written
    (``[checks] accept_inertia``). Attributes as :class:`ModelError`'s."""


class ParameterError(WheeledDynError, ValueError):
    """A physical parameter is not physical (negative mass, inertia violating the triangle
    inequality, ...). Attributes: ``name``, ``value``, ``expected``."""

    def __init__(self, name: str, value: object, expected: str) -> None:
        self.name = name
        self.value = value
        self.expected = expected
        super().__init__(f"parameter {name} = {value!r}: expected {expected}")


class StateError(WheeledDynError, ValueError):
    """A state (configuration or velocity) is malformed: wrong length, NaN, unknown entry.
    Attributes: ``name`` (the entry, or None), ``value``, ``expected``."""

    def __init__(self, name: str | None, value: object, expected: str) -> None:
        self.name = name
        self.value = value
        self.expected = expected
        what = f"state entry {name}" if name else "state"
        super().__init__(f"{what} = {value!r}: expected {expected}")


class DerivationError(InputFileError):
    """A derivation file is well-formed TOML but its content does not fit: an unknown or
    unmapped symbol, a matrix of the wrong shape, coordinates that do not fit the model.
    Attributes as :class:`InputFileError`, plus ``item`` (the key or matrix element)."""

    def __init__(self, path: str | Path, item: str, reason: str, line: int | None = None,
                 column: int | None = None) -> None:
        self.item = item
        super().__init__(path, f"{item}: {reason}", line=line, column=column)


class OptionalDependencyError(WheeledDynError, ImportError):
    """A feature needs a package or program that is not installed. Attributes: ``feature``,
    ``requirement``, ``hint`` (how to install it)."""

    def __init__(self, feature: str, requirement: str, hint: str) -> None:
        self.feature = feature
        self.requirement = requirement
        self.hint = hint
        super().__init__(f"{feature} needs {requirement}: {hint}")


class LimitError(WheeledDynError, ValueError):
    """A number asked for is outside what the toolkit accepts: an option out of its range, or
    a limit that keeps memory and time bounded (states × parameter sets, simulated seconds,
    the size of an expression). Attributes: ``name`` (the option or item), ``value``,
    ``limit`` (the accepted range, as text), ``why`` (what the limit protects, or "")."""

    def __init__(self, name: str, value: object, limit: str, why: str = "") -> None:
        self.name = name
        self.value = value
        self.limit = limit
        self.why = why
        because = f" ({why})" if why else ""
        super().__init__(f"{name} = {value}: expected {limit}{because}")


class WorkerError(WheeledDynError):
    """A worker process of a parallel computation ended without an answer (killed, or a crash
    in compiled code). Attributes: ``reason``, ``files`` (what it may have been working on)."""

    def __init__(self, reason: str, files: Iterable[str] = ()) -> None:
        self.reason = reason
        self.files = tuple(files)
        which = f" while comparing one of: {', '.join(self.files)}" if self.files else ""
        super().__init__(f"{reason}{which}; compare them one by one "
                         "('wheeled-dyn compare MODEL FILE') to find the one")


class ArgumentError(WheeledDynError, ValueError):
    """An argument of a public function is of the wrong type or value (``load_model(123)``,
    ``matrices(phi="abc")``, ``compare(samples=0)``). Attributes: ``function``, ``name`` (the
    argument), ``value`` (as given), ``expected``; the message quotes the value's ``repr``,
    shortened to :data:`SHOWN_CHARS`."""

    def __init__(self, function: str, name: str, value: object, expected: str) -> None:
        self.function = function
        self.name = name
        self.value = value
        self.expected = expected
        super().__init__(f"{function}({name}={_shown(value)}): expected {expected}")


#: Longest ``repr`` of a value an :class:`ArgumentError` quotes (characters).
SHOWN_CHARS = 80


def _shown(value: object) -> str:
    try:
        text = repr(value)
    except Exception:
        text = f"<{type(value).__name__}>"
    return text if len(text) <= SHOWN_CHARS else text[:SHOWN_CHARS - 3] + "..."


class WheeledDynWarning(UserWarning):
    """Something worth knowing that is not an error; the command line prints it as one line
    (``wheeled-dyn: warning: ...``)."""


class CacheWarning(WheeledDynWarning):
    """The disk cache is not used or not written (a folder another user can write, a
    read-only or full disk): the run goes on without it, only slower."""


class ModelWarning(WheeledDynWarning):
    """A model's file asks for something the dynamics do not need and that is not there
    (a mesh file): the model is built without it."""
