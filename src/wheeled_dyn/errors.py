r"""One exception tree for the whole toolkit.

Every error a user can cause (a bad file, an unknown name, a non-physical number) is raised as a
subclass of :class:`WheeledDynError`. Each carries the data needed to act on it as attributes
(``path``, ``line``, ``name``, ``valid`` ...) and a message that names the place and what was
expected. Nothing in the package uses ``assert`` for input validation.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path


def _names(valid: Iterable[str] | None) -> str:
    if valid is None:
        return ""
    items = sorted(str(v) for v in valid)
    return f"; valid: {', '.join(items)}" if items else "; there are none"


class WheeledDynError(Exception):
    """Base class of every error raised by wheeled_dyn on purpose."""


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
        self.valid = tuple(sorted(valid)) if valid is not None else None
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
