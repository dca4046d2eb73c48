"""`wd.compare`: a derivation built from SymPy objects is compared exactly as the same
derivation written as a file (same records, verdicts and causes), errors name
``<python: title>``, and nothing is left in the temporary folder."""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
import sympy as sp

import wheeled_dyn as wd
from wheeled_dyn.compare import ComparisonEngine
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import WheeledDynError

from conftest import SEED
from test_compare_planted import BASE, TRUE_FILE

SAMPLES, PARAM_SETS = 200, 3


def _sympy_tables(changes: dict[tuple, str] = {}) -> dict:
    r"""The true file's matrices as SymPy matrices (as a notebook would have them)."""
    m = {k: [list(r) if isinstance(r, list) else r for r in v]
         for k, v in BASE["matrices"].items()}
    for (key, *index), text in changes.items():
        if len(index) == 1:
            m[key][index[0]] = text
        else:
            m[key][index[0]][index[1]] = text
    return {"A": sp.Matrix(sp.sympify(m["A"])), "C": sp.Matrix(sp.sympify(m["C"])),
            "Q": sp.Matrix(sp.sympify(m["Q"])), "B": sp.Matrix(sp.sympify(m["B"])),
            "symbols": dict(BASE["symbols"]), "inputs": dict(BASE["inputs"]),
            "coordinates": BASE["coordinates"]["use"], "title": "true WIP from a notebook"}


def _summary(result) -> list[tuple]:
    return [(r.element, r.verdict, r.texts) for r in result.records]


def test_api_equals_the_file():
    api = wd.compare("wip", samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED, **_sympy_tables())
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    from_file = engine.compare(load_derivation(TRUE_FILE))
    assert _summary(api) == _summary(from_file)
    assert all(r.verdict == "agrees" for r in api.records) and api.causes == ()
    assert str(api.path) == "<python: true WIP from a notebook>"


def test_api_names_a_planted_error():
    tables = _sympy_tables({("Q", 2): "-g*(MX1*cos(phi) - MY1*sin(phi))"})
    result = wd.compare("wip", samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED, **tables)
    wrong = {r.element: r.texts for r in result.records if r.verdict != "agrees"}
    assert list(wrong) == ["Q[3]"] and wrong["Q[3]"][0].startswith("sign")
    assert [c.kind for c in result.causes] == ["sign"]


def test_api_equations_form():
    acc, vel = sp.symbols("ddx ddpsi ddphi"), sp.symbols("dx dpsi dphi")
    t = _sympy_tables()
    u = sp.Matrix(sp.symbols("u_l u_r"))
    lhs = t["A"] * sp.Matrix(acc) + t["C"] * sp.Matrix(vel) + t["Q"]
    eqs = [sp.Eq(lhs[i], (t["B"] * u)[i]) for i in range(3)]
    tables = {k: v for k, v in t.items() if k not in "ACQB"}
    result = wd.compare("wip", samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED,
                        equations=eqs, **tables)
    assert result.form == "equations"
    assert all(r.verdict == "agrees" for r in result.records), _summary(result)


def test_api_undeclared_symbol_is_one_error():
    tables = _sympy_tables({("A", 0, 0): "m_S + 2*m_C + m_X"})
    before = set(Path(tempfile.gettempdir()).glob("wheeled-dyn-*"))
    with pytest.raises(WheeledDynError) as info:
        wd.compare("wip", **tables)
    message = str(info.value)
    assert "<python: true WIP from a notebook>" in message and "m_X" in message
    assert "A[1,1]" in message
    assert set(Path(tempfile.gettempdir()).glob("wheeled-dyn-*")) == before


def test_compare_is_the_package_and_callable():
    import wheeled_dyn.compare as package
    from wheeled_dyn.compare import ComparisonEngine as engine_class
    assert wd.compare is package and callable(wd.compare)
    assert engine_class is ComparisonEngine


THETA = {"positions": ["theta"], "configuration": {"theta": "theta"}}


@pytest.mark.parametrize("model, tables, words", [
    ("nope", {"coordinates": "full", "A": sp.Matrix([[1]])}, ["unknown model 'nope'"]),
    ("rod_pendulum", {"coordinates": THETA, "A": [["m +* 2"]], "symbols": {"m": "M(rod)"}},
     ["<python: ", "A[1,1]", "not a valid expression"]),
    ("rod_pendulum", {"coordinates": THETA, "A": object()}, ["<python: ", "expected SymPy"]),
    ("rod_pendulum", {"coordinates": THETA, "symbols": {}}, ["nothing to compare"]),
    ("rod_pendulum", {"coordinates": THETA, "A": sp.Matrix([[sp.oo]])}, ["A[1,1]", "'oo'"]),
    ("rod_pendulum", {"coordinates": THETA, "A": sp.Matrix([[1, 0], [0, 1]])},
     ["A: shape", "expected 1×1"]),
    ("rod_pendulum", {"coordinates": THETA, "equations": [sp.Eq(sp.Symbol("theta"),
                                                                 sp.Symbol("theta"))]},
     ["already evaluated to True", "left - right"]),      # not "'True' is a Python keyword"
])
def test_api_bad_input_is_one_error(model, tables, words):
    with pytest.raises(WheeledDynError) as info:
        wd.compare(model, samples=20, param_sets=1, **tables)
    message = str(info.value)
    assert "\n" not in message and all(w in message for w in words), message
    assert "/tmp" not in message and "wheeled-dyn-" not in message      # no temporary path


def test_a_submodule_imported_first_does_not_hide_the_api_function():
    r"""``wd.simulate`` is the function even after ``wheeled_dyn.simulate.reduced`` (a module
    of the sub-package of the same name) was imported: in a fresh interpreter."""
    import subprocess
    import sys
    code = ("import wheeled_dyn.simulate.reduced\nfrom wheeled_dyn import simulate\n"
            "import wheeled_dyn as wd\nprint(callable(simulate), type(simulate).__name__, "
            "callable(wd.compare))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["True", "function", "True"]


def test_one_engine_tells_two_derivations_of_one_title_apart(tmp_path):
    r"""One engine kept for several derivations built in Python with the same title (their
    path is ``<python: title>``, which has no file): the second, with a wrong A[1,1], is
    compared, not given the first's result."""
    from wheeled_dyn.derivations.from_python import derivation_from_sympy
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    right = derivation_from_sympy("wip", **_sympy_tables())
    wrong = derivation_from_sympy("wip", **_sympy_tables({("A", 0, 0): "2*m_C"}))
    assert right.path == wrong.path
    assert all(r.verdict == "agrees" for r in engine.compare(right).records)
    assert any(r.element == "A[1,1]" and r.verdict == "differs"
               for r in engine.compare(wrong).records)
    assert all(r.verdict == "agrees" for r in engine.compare(right).records)


#: The hinged uniform rod (seed 000's 4.4): m l²/3 θ̈ + m g l/2 sin θ = 0.
_ROD = {"coordinates": {"positions": ["theta"], "configuration": {"theta": "theta"}},
        "C": sp.zeros(1, 1), "assumes": {"uniform": ["rod"]}}
_m, _l, _g, _th = sp.symbols("m l g theta")
_ROD_NAMES = {"m": "M(rod)", "l": "length(rod)", "g": "g"}


@pytest.mark.parametrize("number", [sp.E, sp.EulerGamma])
def test_sympys_named_numbers_are_numbers_not_the_documents_symbols(number):
    r"""SymPy's E (Euler's number) and other named constants were printed as their names and
    read back as the document's symbols: with a symbol E declared 1, A = e·m l²/3 "agreed".
    They are numbers: the element differs, declared E or not."""
    Q = sp.Matrix([_m * _g * _l / 2 * sp.sin(_th)])
    result = wd.compare("rod_pendulum", A=sp.Matrix([[number * _m * _l ** 2 / 3]]), Q=Q,
                        symbols={**_ROD_NAMES, "E": "1", "EulerGamma": "1"},
                        samples=SAMPLES, param_sets=PARAM_SETS, **_ROD)
    records = {r.element: r for r in result.records}
    assert records["A[1,1]"].verdict == Verdict.DIFFERS
    right = wd.compare("rod_pendulum", A=sp.Matrix([[_m * _l ** 2 / 3]]), Q=Q,
                       symbols=_ROD_NAMES, samples=SAMPLES, param_sets=PARAM_SETS, **_ROD)
    assert right.equivalent is True


def test_the_imaginary_unit_is_one_clear_error():
    with pytest.raises(WheeledDynError, match="imaginary unit"):
        wd.compare("rod_pendulum", A=sp.Matrix([[sp.I * _m * _l ** 2 / 3]]),
                   Q=sp.Matrix([_m * _g * _l / 2 * sp.sin(_th)]),
                   symbols={**_ROD_NAMES, "I": "1"}, **_ROD)
