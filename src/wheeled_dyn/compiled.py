r"""SymPy expressions compiled to NumPy functions, as ``sympy.lambdify(args, expr, "numpy")``
compiles them (the same code, so the same numbers), in about half its time.

A comparison compiles a few hundred expressions (a document's elements, the trial expressions
of its diagnoses, its steps' components). Besides printing the code, ``lambdify`` sorts the
arguments by SymPy's canonical order (to name the dummies it may need), walks the expression
for implemented functions, prints the expression once more for the function's docstring and
registers the source for tracebacks, all for features the comparison does not use.
:func:`numpy_function` skips them when the arguments are plain symbols with names that are
Python identifiers (which need no dummies), calls ``lambdify`` itself otherwise, and prints
each subexpression once (:class:`_RememberingPrinter`). Measured on seed 001's default
report in one process, before the code was remembered (below): its 721 compilations took
0.48 s instead of 1.07 s.

The code written is remembered across runs (the disk cache's ``compiled/numpy-<code>.pickle``,
a :class:`~wheeled_dyn.disk_cache.DiskMemo` named by SymPy's version and this file), keyed by
the argument names, the expression and ``cse``: compiling the same expression again only
executes its code. That file is signed and read only from the user's own private cache
(:mod:`wheeled_dyn.disk_cache`, docs/cache.md): code altered or planted there is never
executed, and with ``WHEELED_DYN_REUSE=0`` none is read (every function is written anew).

It builds on two of SymPy's internals, ``lambdify``'s function printer and its NumPy
namespace (a SymPy release without them gets ``lambdify`` itself);
``tests/test_compiled_functions.py`` checks that the code is ``lambdify``'s.
"""

from __future__ import annotations

import builtins
import functools
import itertools
import keyword
from collections.abc import Callable, Hashable, Sequence
from pathlib import Path

import sympy as sp
from sympy.printing.numpy import NumPyPrinter

from .disk_cache import DiskMemo

try:                                  # SymPy's internals: where they moved, lambdify itself
    from sympy.utilities.lambdify import MODULES, _EvaluatorPrinter, _import
except ImportError:                   # pragma: no cover - depends on the SymPy release
    MODULES = _import = None
    _EvaluatorPrinter = object

#: The settings ``lambdify`` gives its NumPy printer.
_PRINTER_SETTINGS = {"fully_qualified_modules": False, "inline": True,
                     "allow_unknown_functions": True, "user_functions": {}}


class _RememberingPrinter(NumPyPrinter):
    r"""``lambdify``'s NumPy printer that prints each subexpression once per process: below
    the top (where a float prints with all its digits), what a subexpression prints as
    depends on it alone, and the trial expressions of the diagnoses share most of theirs with
    the element they come from."""

    _printed: dict[tuple, str] = {}

    def _print(self, expr, **kwargs) -> str:
        if self._print_level < 1 or not isinstance(expr, sp.Basic):
            return super()._print(expr, **kwargs)
        key = (expr, tuple(sorted(kwargs.items())))
        text = self._printed.get(key)
        if text is None:
            unsupported = len(self._not_supported)
            text = super()._print(expr, **kwargs)
            if len(self._not_supported) == unsupported:     # a complete translation
                self._printed[key] = text
        return text


class _PlainArguments(_EvaluatorPrinter):
    r"""``lambdify``'s function printer for arguments that are plain, safely named symbols:
    their names as they are, no canonical sorting (which only orders the dummies)."""

    def _preprocess(self, args, expr, cses=(), _dummies_dict=None):
        return [str(a) for a in args], expr


def _plain(args: Sequence) -> bool:
    return all(isinstance(a, sp.Symbol) and not isinstance(a, sp.Dummy)
               and a.name.isidentifier() and not keyword.iskeyword(a.name) for a in args)


#: The code of compiled functions and the modules' names it imports, remembered across runs.
SOURCES = DiskMemo("compiled", "numpy", lambda: [Path(__file__)])


def _frozen(expr) -> Hashable:
    r"""``expr`` as a key: nested lists and tuples as tagged tuples, matrices immutable."""
    if isinstance(expr, (list, tuple)):
        return (type(expr).__name__, *(_frozen(e) for e in expr))
    if isinstance(expr, sp.MatrixBase):
        return (type(expr).__name__, sp.ImmutableMatrix(expr))
    return expr


#: The functions made in this process, by key and code (at most :data:`MADE_LIMIT`): a
#: comparison compiles the same element again for several readings, and a function made from
#: the same code is the same function. Looked up with the code :data:`SOURCES` serves, so that
#: memo still records every code a run used, and code served otherwise (its file read again)
#: is run as served.
_MADE: dict[tuple[tuple, str], Callable] = {}
MADE_LIMIT = 20_000


@functools.cache
def _numpy_namespace() -> dict[str, object]:
    r"""The names ``lambdify`` gives NumPy code (SymPy's defaults, then ``import numpy; from
    numpy import *; from numpy.linalg import *``, its translations and ``Abs``) without the
    submodules NumPy loads on first touch (``testing``, ``f2py``, ``ma``, ``random`` ...):
    a star import loads them all, a tenth of a second per process, and no printed code names
    them."""
    import numpy
    _, default, translations, _ = MODULES["numpy"]
    namespace: dict[str, object] = {**default, "numpy": numpy}
    namespace.update({n: numpy.__dict__[n] for n in numpy.__all__ if n in numpy.__dict__})
    namespace.update({n: getattr(numpy.linalg, n) for n in numpy.linalg.__all__})
    for sympy_name, name in translations.items():
        namespace[sympy_name] = namespace[name]
    namespace.setdefault("Abs", abs)
    return namespace


def numpy_function(args: Sequence[sp.Symbol], expr, cse: bool = False) -> Callable:
    r"""``sympy.lambdify(args, expr, "numpy", cse=cse)`` (``expr`` an expression or a nested
    list or tuple of them), without a docstring; its code remembered (:data:`SOURCES`)."""
    if _import is None or not _plain(args):
        return sp.lambdify(args, expr, "numpy", cse=cse, docstring_limit=0)
    key = (tuple(a.name for a in args), _frozen(expr), cse)
    source, imports = SOURCES.get(key, lambda: _written(args, expr, cse))
    made = _MADE.get((key, source))
    if made is not None:
        return made
    namespace = dict(_numpy_namespace())
    if hasattr(expr, "atoms"):
        namespace.update({str(s): s for s in expr.atoms(sp.Symbol)})
    for module, names in imports:
        for name in names:
            if name not in namespace:
                exec(f"from {module} import {name}", {}, namespace)
    namespace.update({"builtins": builtins, "range": range})
    local: dict[str, Callable] = {}
    exec(compile(source, "<compiled>", "exec"), namespace, local)
    if len(_MADE) >= MADE_LIMIT:
        _MADE.clear()
    made = _MADE[(key, source)] = local["_lambdifygenerated"]
    return made


def grouped_function(groups: Sequence[Sequence[sp.Symbol]], expr) -> Callable:
    r"""``sympy.lambdify(groups, expr, "numpy")`` for arguments in groups — ``f(q, p)`` with
    ``q`` and ``p`` sequences of values — as :func:`numpy_function` of the symbols in order."""
    flat = numpy_function([s for group in groups for s in group], expr)

    def grouped(*values) -> object:
        return flat(*itertools.chain.from_iterable(values))

    return grouped


def _written(args: Sequence[sp.Symbol], expr, cse: bool) -> tuple[str, tuple]:
    r"""The code ``lambdify`` writes for ``expr`` and the names it imports, by module."""
    printer = _RememberingPrinter(dict(_PRINTER_SETTINGS))
    cses, body = sp.cse(expr, list=False) if cse else ((), expr)
    source = _PlainArguments(printer).doprint("_lambdifygenerated", list(args), body,
                                              cses=cses)
    return source, tuple((m, tuple(sorted(n))) for m, n in printer.module_imports.items())


__all__ = ["SOURCES", "grouped_function", "numpy_function"]
