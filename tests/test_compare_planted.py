"""The comparison engine on a derivation known to be right, and on copies with one planted error.

``tests/data/wip_true_seed001.toml`` holds the true reduced equations of the WIP in the
``seed001`` coordinates, derived by hand for general parameters (products of inertia, centre of
mass off the axis, motor armature). It is first checked against :class:`CoordinateMap` directly,
without the engine; then the engine must find it right everywhere, and on each planted copy
name exactly the planted element with the right diagnosis and leave everything else agreeing.
A planted error in C also changes the h coefficients of its row: those are asserted too.
"""

from __future__ import annotations

import copy
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model, random_wip_parameters
from wheeled_dyn import standard_parameters
from wheeled_dyn.compare import ComparisonEngine, DerivationResult
from wheeled_dyn.derivations import load_derivation

from conftest import SEED

TRUE_FILE = Path(__file__).parent / "data" / "wip_true_seed001.toml"
#: Small grid: the planted errors are structural, a few hundred states show them.
SAMPLES, PARAM_SETS = 200, 3
#: Relative tolerance of the direct check of the true file against CoordinateMap.
DIRECT_TOL = 1e-10


# -- the true file, checked without the engine ---------------------------------------------

def _symbol_values(p) -> dict[str, float]:
    r"""The true file's symbols at physical parameters ``p`` (written out here, not taken
    from the engine's parameter namespace)."""
    body = standard_parameters(p.as_dict())["body"]
    values = {name: getattr(p, name) for name in ("m_S", "m_C", "R", "L", "g", "Iw2", "Iw3",
                                                  "I_a")}
    values.update({f"{k}1": float(body[k]) for k in ("MX", "MY", "MZ", "XX", "XY", "XZ", "YY",
                                                     "YZ", "ZZ")})
    return values


def test_true_file_equals_coordinate_map_directly():
    d = load_derivation(TRUE_FILE)
    rng = np.random.default_rng(SEED)
    args = [*d.positions, *d.velocities]
    for _ in range(3):
        p = random_wip_parameters(rng)
        assert abs(p.I_a) > 0 and abs(p.d_x) > 0 and abs(p.Ixz) > 0     # general parameters
        wm = load_model("wip", p)
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))
        sub = {d.symbol(k): v for k, v in _symbol_values(p).items()}
        fns = {key: sp.lambdify(args, getattr(d, key).xreplace(sub), "numpy")
               for key in ("A", "C", "Q", "B")}
        for _ in range(10):
            q, nu = rng.uniform(-np.pi, np.pi, 3), rng.normal(size=3)
            truth = cmap.terms(q, nu)
            for key, fn in fns.items():
                mine = np.asarray(fn(*q, *nu), dtype=float).reshape(np.shape(getattr(truth, key)))
                true = getattr(truth, key)
                err = np.abs(mine - true).max()
                assert err <= DIRECT_TOL * max(1.0, np.abs(true).max()), (
                    f"{key} of {TRUE_FILE.name} differs from CoordinateMap by {err:.3g} at "
                    f"q={q}, nu={nu}, parameters {p}")


# -- planted copies -------------------------------------------------------------------------

def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"no TOML for {v!r}")


def _dumps(data: dict) -> str:
    r"""TOML text of a derivation-file dict (strings, booleans, lists, one level of tables)."""
    lines = [f"{k} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for name, table in data.items():
        if isinstance(table, dict):
            lines.append(f"\n[{name}]")
            lines += [f"{k} = {_toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


BASE = tomllib.loads(TRUE_FILE.read_text())


def _planted(tmp_path: Path, changes: dict[tuple, str]) -> Path:
    r"""A copy of the true file with elements replaced: ``{("A", 2, 0): "text"}`` (0-based)."""
    data = copy.deepcopy(BASE)
    for (key, *index), text in changes.items():
        M = data["matrices"][key]
        if len(index) == 1:
            assert M[index[0]] != text
            M[index[0]] = text
        else:
            assert M[index[0]][index[1]] != text
            M[index[0]][index[1]] = text
    path = tmp_path / "planted.toml"
    path.write_text(_dumps(data))
    return path


@pytest.fixture(scope="module")
def engine() -> ComparisonEngine:
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _records(result: DerivationResult) -> dict:
    return {r.element: r for r in result.records}


def _others_agree(result: DerivationResult, expected: set[str]) -> None:
    wrong = [(r.element, r.verdict, r.texts) for r in result.records
             if r.element not in expected and r.verdict != "agrees"]
    assert not wrong, f"elements other than {sorted(expected)} do not agree: {wrong}"
    assert result.row_factors == (None, None, None), result.row_factors


def test_true_file_agrees_everywhere(engine):
    result = engine.compare(load_derivation(TRUE_FILE))
    assert len(result.records) == 9 + 9 + 3 + 6 + 18
    _others_agree(result, set())
    assert result.energy is not None and result.energy.conserves, result.energy
    assert result.asymmetric == ()
    assert result.notes == ()


#: (id, changes, {element: (verdict, diagnosis prefix)}, conserves energy, asymmetric)
PLANTED = [
    ("sign Q3", {("Q", 2): "-g*(MX1*cos(phi) - MY1*sin(phi))"},
     {"Q[3]": ("differs", "sign:")}, True, ()),
    ("sign C32", {("C", 2, 1): "dpsi*((XX1 - YY1)*sin(2*phi)/2 + XY1*cos(2*phi))"},
     {"C[3,2]": ("differs", "sign:"), "h[3]:dpsi*dpsi": ("differs", "sign:")}, False, ()),
    # one term of a velocity product's coefficient with the wrong sign: named in h too (h's
    # products had no term diagnoses: it was a factor "if" some family held, or nothing)
    ("sign of one term C32", {("C", 2, 1): "-dpsi*((XX1 - YY1)*sin(2*phi)/2 - XY1*cos(2*phi))"},
     {"C[3,2]": ("differs", "sign: the term"), "h[3]:dpsi*dpsi": ("differs", "sign: the term")},
     False, ()),
    ("factor 2 A33", {("A", 2, 2): "2*(ZZ1 + 2*I_a)"},
     {"A[3,3]": ("differs", "factor: the document is 2 × the truth")}, True, ()),
    ("factor 1/2 C22", {("C", 1, 1): "dphi*((XX1 - YY1)*sin(2*phi)/2 + XY1*cos(2*phi))/2"},
     {"C[2,2]": ("differs", "factor: the document is 1/2 × the truth"),
      # h2's dpsi*dphi coefficient is C22's plus C23's, equal halves: 3/4 of it remain
      "h[2]:dpsi*dphi": ("differs", "factor: the document is 3/4 × the truth")}, False, ()),
    ("swap dphi for dpsi C12", {("C", 0, 1): "dphi*(MY1*sin(phi) - MX1*cos(phi))"},
     {"C[1,2]": ("differs", "swap: dphi where dpsi fits"),
      "h[1]:dpsi*dpsi": ("differs", "missing:"),
      "h[1]:dpsi*dphi": ("differs", "extra term:")}, False, ()),
    ("missing C21", {("C", 1, 0): "0"},
     {"C[2,1]": ("differs", "missing:"), "h[2]:dx*dpsi": ("differs", "missing:")}, False, ()),
    ("units Iw3/R in A11", {("A", 0, 0): "m_S + 2*m_C + 2*Iw3/R + 2*I_a/R**2"},
     {"A[1,1]": ("differs", "dimension: term 2*Iw3/R is kg·m beside kg")}, True, ()),
    ("units 1/R**2 in B11", {("B", 0, 0): "-1/R**2"},
     {"B[1,1]": ("differs", "dimension: has m^-2, expected m^-1")}, True, ()),
    ("asymmetric A31", {("A", 2, 0): "-2*I_a/R - MX1*sin(phi) - MY1*cos(phi)"},
     {"A[3,1]": ("differs", "sign: the term -2*I_a/R has the wrong sign")},
     True, ("A[1,3] ≠ A[3,1]",)),
]


@pytest.mark.parametrize("changes, expected, conserves, asymmetric",
                         [p[1:] for p in PLANTED], ids=[p[0] for p in PLANTED])
def test_planted_error_is_named(engine, tmp_path, changes, expected, conserves, asymmetric):
    result = engine.compare(load_derivation(_planted(tmp_path, changes)))
    records = _records(result)
    for element, (verdict, prefix) in expected.items():
        r = records[element]
        assert r.verdict == verdict, (element, r.verdict, r.texts)
        assert any(x.startswith(prefix) for x in r.texts), (element, r.texts)
    _others_agree(result, set(expected))
    assert result.energy is not None and result.energy.conserves is conserves, result.energy
    assert result.asymmetric == asymmetric


def test_planted_swap_in_h_is_paired(engine, tmp_path):
    r"""φ̇ written for ψ̇ in C[1,2] turns the true ψ̇² term of h1 into a ψ̇φ̇ term: the two
    h records point at each other."""
    result = engine.compare(load_derivation(_planted(
        tmp_path, {("C", 0, 1): "dphi*(MY1*sin(phi) - MX1*cos(phi))"})))
    records = _records(result)
    assert "swap: written as dpsi*dphi in the document" in records["h[1]:dpsi*dpsi"].texts
    assert ("swap: the document's dpsi*dphi term is the true dpsi*dpsi term"
            in records["h[1]:dpsi*dphi"].texts)


MISSING_TERM = {("A", 1, 1): "2*m_C*L**2 + 2*Iw3*L**2/R**2 + 2*I_a*L**2/R**2 "
                             "+ XX1*sin(phi)**2 + XY1*sin(2*phi) + YY1*cos(phi)**2"}


def test_planted_missing_term_differs_alone(engine, tmp_path):
    r"""2 Iw2 dropped from A[2,2]: that element differs, nothing else."""
    result = engine.compare(load_derivation(_planted(tmp_path, MISSING_TERM)))
    assert _records(result)["A[2,2]"].verdict == "differs"
    _others_agree(result, {"A[2,2]"})
    assert result.energy.conserves                       # a constant term does no work


def test_planted_missing_term_is_named(engine, tmp_path):
    result = engine.compare(load_derivation(_planted(tmp_path, MISSING_TERM)))
    r = _records(result)["A[2,2]"]
    named = " ".join(r.texts) + " " + (r.residual or "")
    assert "Iw2" in named, (r.texts, r.residual)


def test_undeclared_row_factor_is_a_row_factor(engine, tmp_path):
    r"""Row 2 multiplied through by -1 (as Kane's generalised inertia forces are): reported as
    a row factor, every element agrees once it is divided out."""
    changes = {}
    for key in ("A", "C", "B"):
        for j, text in enumerate(BASE["matrices"][key][1]):
            changes[(key, 1, j)] = f"-({text})"
    changes[("Q", 1)] = "-(0)"
    result = engine.compare(load_derivation(_planted(tmp_path, changes)))
    assert result.row_factors == (None, "-1", None)
    wrong = [(r.element, r.verdict, r.texts) for r in result.records if r.verdict != "agrees"]
    assert not wrong, wrong
    assert result.energy.conserves and result.asymmetric == ()
