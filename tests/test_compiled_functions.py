"""compiled.py writes the code sympy.lambdify writes (so the comparison's numbers do not
change), reuses what it printed before, and hands unusual arguments to lambdify itself."""

from __future__ import annotations

import linecache

import numpy as np
import pytest
import sympy as sp

from wheeled_dyn import compiled
from wheeled_dyn.compiled import numpy_function

x, y, phi = sp.symbols("x y phi", real=True)
m, d = sp.symbols("m d", positive=True)
EXPRESSIONS = [
    m * d ** 2 * sp.cos(phi) ** 2 + sp.Rational(1, 3) * m * x - 2.5 * y,
    sp.sqrt(m) / d + x ** -2 + sp.Float("0.1", 30) * sp.sin(phi - y),
    sp.Float(2.0),
    [m * x * y, sp.Integer(0), sp.exp(-phi) * sp.Abs(x)],
    (d * sp.cos(phi) * sp.sin(phi) + m * d * sp.sin(phi) ** 2, m),
]
ARGS = [x, y, phi, m, d]


def _source(fn) -> str:
    return "".join(linecache.cache[fn.__code__.co_filename][2])


def _written(expr, cse: bool) -> str:
    printer = compiled._RememberingPrinter(dict(compiled._PRINTER_SETTINGS))
    cses, body = sp.cse(expr, list=False) if cse else ((), expr)
    return compiled._PlainArguments(printer).doprint("_lambdifygenerated", ARGS, body, cses=cses)


@pytest.mark.parametrize("cse", [False, True])
@pytest.mark.parametrize("expr", EXPRESSIONS, ids=range(len(EXPRESSIONS)))
def test_same_code_and_numbers_as_lambdify(expr, cse):
    reference = sp.lambdify(ARGS, expr, "numpy", cse=cse)
    for _ in range(2):                         # printed afresh, then from what was remembered
        assert _written(expr, cse) == _source(reference)
    rng = np.random.default_rng(3)
    argv = [rng.uniform(0.5, 2.0, 50) for _ in ARGS]
    ours = numpy_function(ARGS, expr, cse=cse)(*argv)
    theirs = reference(*argv)
    for a, b in zip(np.broadcast_arrays(*ours) if isinstance(ours, (list, tuple)) else [ours],
                    np.broadcast_arrays(*theirs) if isinstance(theirs, (list, tuple))
                    else [theirs]):
        assert np.array_equal(np.asarray(a), np.asarray(b))


def test_arguments_lambdify_must_rename_go_to_lambdify():
    odd = sp.Symbol("lambda")                  # a Python keyword: lambdify makes a dummy
    dummy = sp.Dummy("u")
    f = numpy_function([odd, dummy], odd * 2 + dummy)
    assert f(1.5, 2.0) == 5.0


def test_the_names_given_to_the_code_are_lambdifys_without_numpys_submodules():
    r"""In a fresh interpreter, the namespace the compiled code runs in holds every name of
    ``lambdify``'s NumPy namespace, each the same object, except the NumPy submodules a star
    import loads (``testing``, ``f2py`` ...); making it loads none of them (a compiled
    function is made and run before lambdify's namespace is)."""
    import subprocess
    import sys
    code = (
        "import sys, importlib\n"
        "import sympy as sp\n"
        "from wheeled_dyn import compiled\n"
        "x = sp.Symbol('x', real=True)\n"
        "f = compiled.numpy_function([x], [sp.sin(x) + sp.Abs(x), sp.Heaviside(x)], cse=True)\n"
        "assert abs(f(0.5)[0] - 0.979425538604203) < 1e-15, f(0.5)\n"
        "loaded = [m for m in ('numpy.testing', 'numpy.f2py', 'numpy.ma') if m in sys.modules]\n"
        "assert not loaded, loaded\n"
        "mine = dict(compiled._numpy_namespace())\n"
        "L = importlib.import_module('sympy.utilities.lambdify')\n"
        "L._import('numpy')\n"
        "ref = L.MODULES['numpy'][0]\n"
        "import types\n"
        "extra = {k for k in set(ref) - set(mine) if isinstance(ref[k], types.ModuleType)}\n"
        "assert set(mine) == set(ref) - extra, (set(mine) ^ set(ref)) - extra\n"
        "assert all(mine[k] is ref[k] for k in mine)\n"
        "print(sorted(extra))\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "testing" in done.stdout
