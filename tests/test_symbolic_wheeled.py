"""Closed forms of wheeled models in document coordinates (symbolic/wheeled.py) against the
numeric reduction (CoordinateMap, Pinocchio), for random states and random physical parameter
sets; seed 001's eq. (25) against the truth element by element; labels, caches and the CLI."""

from __future__ import annotations

import argparse
import json
import time

from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from sympy.core.function import AppliedUndef

from conftest import SEED
from wheeled_dyn import (CoordinateMap, builtin_coordinate_set, load_model,
                         random_wip_parameters, standard_parameters)
from wheeled_dyn.coordinates import parse_coordinate_set
from wheeled_dyn.errors import ModelError, OptionalDependencyError, UnknownNameError
from wheeled_dyn.symbolic import (
    element_expressions, lambdify_terms, parameter_vector, physical_symbols, simplify_expr,
    true_expressions, velocity_products, wheeled_symbolic)
from wheeled_dyn.cli import symbolic_cmd as symbolic_commands
from wheeled_dyn.symbolic import wheeled as wheeled_module

#: Agreement required between closed forms and the numeric reduction (relative to the
#: largest entry of the matrix, or 1).
REL_TOL = 1e-9
#: Random parameter sets and states per coordinate set.
N_PARAM_SETS, N_STATES = 2, 4
#: Largest time of the first (cold) call of true_expressions for the WIP in seed001 (s).
FIRST_CALL_SECONDS = 5.0
WIP_SETS = ("seed001", "wheels", "absolute_wheels", "full")

#: Coordinate sets as derivation files write them (seed 001's report [3] and Kim's paper):
#: fewer velocities than rolling motions (minimum-norm S), and a sign-flipped pitch.
DOCUMENT_SETS = {
    "no_heading": {"kind": "quasi", "rolling": "eliminate", "positions": ["x", "theta"],
                   "configuration": {"psi": "0", "phi": "-theta"},
                   "velocity_map": {"dx": "cos(psi)*dx0 + sin(psi)*dy0", "dtheta": "-dphi"}},
    "flipped_pitch": {"kind": "quasi", "rolling": "eliminate",
                      "positions": ["x", "psi", "theta"],
                      "configuration": {"psi": "psi", "phi": "-theta"},
                      "velocity_map": {"dx": "cos(psi)*dx0 + sin(psi)*dy0", "dpsi": "dpsi",
                                       "dtheta": "-dphi"}},
    "wheel_heading": {"kind": "holonomic", "rolling": "multipliers",
                      "positions": ["x0", "y0", "theta_l", "theta_r", "phi"],
                      "configuration": {"x0": "x0", "y0": "y0",
                                        "psi": "R*(theta_l - theta_r)/L", "phi": "phi",
                                        "theta_l": "-theta_l - phi",
                                        "theta_r": "-theta_r - phi"}},
}


def _relative_error(got: np.ndarray, want: np.ndarray) -> float:
    return float(np.abs(got - want).max() / max(1.0, np.abs(want).max()))


def _check_against_numeric(wm, cs, red, values, rng, context: str) -> None:
    f = lambdify_terms(red)
    cmap = CoordinateMap(wm, cs)
    names = set(red.terms())
    assert {"A", "C", "Q", "h", "B"} <= names, names
    if cs.rolling == "multipliers":
        assert "G" in names, f"{context}: no G for a set with multipliers"
    for s in range(N_STATES):
        q = rng.uniform(-np.pi, np.pi, len(cs.positions))
        nu = rng.normal(size=len(cs.velocities))
        want = cmap.terms(q, nu)
        for name in names:
            got = f(name, q, nu, values)
            err = _relative_error(got, getattr(want, name))
            assert err < REL_TOL, (f"{context}, state {s} (q={q}, nu={nu}): {name} differs by "
                                   f"{err:.2e}\nsymbolic {got}\nnumeric {getattr(want, name)}")


@pytest.mark.parametrize("coords", WIP_SETS)
def test_wip_physical_closed_forms_equal_the_numeric_reduction(coords):
    """Physical symbols (every product of inertia, centre-of-mass offset and the armature
    nonzero) give the numbers of CoordinateMap for random parameter sets and states."""
    rng = np.random.default_rng(SEED)
    for k in range(N_PARAM_SETS):
        p = random_wip_parameters(rng)
        wm = load_model("wip", p)
        cs = builtin_coordinate_set(wm, coords)
        red = wheeled_symbolic(wm, cs, "physical")
        assert red.nu == cs.velocity_symbols() and red.q == cs.position_symbols()
        assert all(s.is_real for s in red.parameters), red.parameters
        values = parameter_vector(red, values=p.as_dict())
        _check_against_numeric(wm, cs, red, values, rng, f"wip {coords}, parameter set {k}")


@pytest.mark.parametrize("mode", ["numbers", "standard"])
def test_wip_numbers_and_standard_parameters(mode):
    rng = np.random.default_rng(SEED + 1)
    wm = load_model("wip", random_wip_parameters(rng))
    cs = builtin_coordinate_set(wm, "seed001")
    red = wheeled_symbolic(wm, cs, mode)
    if mode == "numbers":
        assert red.parameters == (), red.parameters
    else:
        assert {"M_body", "ZZ_body", "M_wheel_left"} <= {s.name for s in red.parameters}
    _check_against_numeric(wm, cs, red, parameter_vector(red, wm.model), rng, f"wip {mode}")


@pytest.mark.parametrize("name", sorted(DOCUMENT_SETS))
def test_document_coordinate_sets(name):
    """Sets written by documents: a missing heading (minimum-norm S, as the pseudo-inverse of
    the numeric reduction), a sign-flipped pitch, wheel angles defining the heading."""
    rng = np.random.default_rng(SEED + 2)
    p = random_wip_parameters(rng)
    wm = load_model("wip", p)
    cs = parse_coordinate_set(DOCUMENT_SETS[name], name, wm.coordinate_names, ("R", "L"))
    red = wheeled_symbolic(wm, cs, "physical")
    _check_against_numeric(wm, cs, red, parameter_vector(red, values=p.as_dict()), rng,
                           f"document set {name}")


#: Models whose closed forms are checked in their heading coordinates: TIAGo's base, and
#: Upkie with its legs locked at a crouch (the locked joints' rotations leave float noise,
#: 1e-16, in the rolling constraints; the elimination runs over exact numbers).
HEADING_MODELS = ("tiago_base", str(Path(__file__).parent / "data" / "upkie_crouch"
                                    / "upkie_crouch.toml"))


@pytest.mark.parametrize("mode", ["numbers", "standard"])
@pytest.mark.parametrize("model", HEADING_MODELS, ids=["tiago_base", "upkie_crouch"])
def test_heading_closed_forms(model, mode):
    try:
        wm = load_model(model)
    except OptionalDependencyError as exc:
        pytest.skip(str(exc))
    cs = builtin_coordinate_set(wm, "heading")
    red = wheeled_symbolic(wm, cs, mode)
    _check_against_numeric(wm, cs, red, parameter_vector(red, wm.model),
                           np.random.default_rng(SEED + 3), f"{Path(model).stem} {mode}")


def test_seed001_closed_form_reads_as_expected():
    """Spot checks of the printed forms: the armature couples x and phi through the wheels,
    the heading speed's Boltzmann-Hamel term m_S d sin(phi) dpsi**2 is in h_1."""
    wm = load_model("wip")
    P = physical_symbols()
    red = wheeled_symbolic(wm, builtin_coordinate_set(wm, "seed001"))
    phi = sp.Symbol("phi", real=True)
    dpsi = sp.Symbol("dpsi", real=True)
    expect_A11 = P["m_S"] + 2 * P["m_C"] + 2 * (P["Iw3"] + P["I_a"]) / P["R"] ** 2
    assert sp.expand(red.A[0, 0] - expect_A11) == 0, red.A[0, 0]
    coeff = velocity_products(red.h[0], red.nu)[(1, 1)]
    want = P["m_S"] * (P["d"] * sp.sin(phi) - P["d_x"] * sp.cos(phi))
    assert sp.expand(coeff - want) == 0, coeff
    assert red.B == sp.Matrix([[-1 / P["R"], -1 / P["R"]], [P["L"] / P["R"], -P["L"] / P["R"]],
                               [-1, -1]]), red.B
    assert dpsi in red.h.free_symbols


# -- seed 001, eq. (25) --------------------------------------------------------------------
#: Elements of eq. (25) equal to the truth once the armature is set to zero.
EQ25_RIGHT = ("A[1,1]", "A[1,2]", "A[1,3]", "A[2,1]", "A[2,2]", "A[2,3]", "A[3,1]", "A[3,2]",
              "A[3,3]", "C[1,1]", "C[1,3]", "C[2,2]", "C[2,3]", "C[3,1]", "C[3,3]",
              "Q[1]", "Q[2]", "Q[3]")
#: Elements that differ, and why: the quasi-velocity term S^T A Sdot eq. (25) lacks, and the
#: printed phi-dot/2 where the appendix has psi-dot/2.
EQ25_WRONG = ("C[1,2]", "C[2,1]", "C[3,2]")


@pytest.fixture(scope="module")
def eq25():
    from wheeled_dyn.derivations import load_derivation
    from wheeled_dyn.paths import DATA_DIR
    d = load_derivation(DATA_DIR / "derivations" / "seed001" / "eq25_lagrange.toml")
    P = physical_symbols()
    std = standard_parameters(P)
    mapping = {s.symbol: s.value for s in d.symbols.values() if s.value is not None}

    def in_physical(expr):
        out = sp.sympify(expr).xreplace(mapping)
        calls = {c: std[str(c.args[0])][c.func.__name__] for c in out.atoms(AppliedUndef)}
        out = out.xreplace(calls)
        return out.xreplace({s: P.get(s.name, s) for s in out.free_symbols})

    doc = {}
    for key, M in (("A", d.A), ("C", d.C)):
        for i in range(3):
            for j in range(3):
                doc[f"{key}[{i + 1},{j + 1}]"] = in_physical(M[i, j])
    for i in range(3):
        doc[f"Q[{i + 1}]"] = in_physical(d.Q[i])
    truth = true_expressions("wip", builtin_coordinate_set(load_model("wip"), "seed001"))
    return doc, truth, P


def _residual(truth, doc, P, I_a=0):
    return simplify_expr(sp.expand((truth - doc).xreplace({P["I_a"]: I_a})))


@pytest.mark.parametrize("element", EQ25_RIGHT)
def test_eq25_elements_that_are_right(eq25, element):
    doc, truth, P = eq25
    assert _residual(truth[element], doc[element], P) == 0, (element, truth[element],
                                                               doc[element])


@pytest.mark.parametrize("element", EQ25_WRONG)
def test_eq25_elements_that_differ(eq25, element):
    doc, truth, P = eq25
    assert _residual(truth[element], doc[element], P) != 0, element


def test_eq25_misses_the_armature(eq25):
    doc, truth, P = eq25
    got = _residual(truth["A[1,1]"], doc["A[1,1]"], P, I_a=P["I_a"])
    assert sp.simplify(got - 2 * P["I_a"] / P["R"] ** 2) == 0, got


def test_eq25_c12_residual_is_the_boltzmann_hamel_term(eq25):
    doc, truth, P = eq25
    phi, dpsi = sp.Symbol("phi", real=True), sp.Symbol("dpsi", real=True)
    got = _residual(truth["C[1,2]"], doc["C[1,2]"], P)
    want = P["m_S"] * dpsi * (P["d"] * sp.sin(phi) - P["d_x"] * sp.cos(phi))
    assert sp.expand(got - want) == 0, got


# -- labels and caches ----------------------------------------------------------------------
def test_true_expression_labels_and_h_coefficients():
    wm = load_model("wip")
    cs = builtin_coordinate_set(wm, "seed001")
    truth = true_expressions("wip", cs)
    red = wheeled_symbolic(wm, cs)
    n = 3
    want = ({f"A[{i},{j}]" for i in range(1, n + 1) for j in range(1, n + 1)}
            | {f"C[{i},{j}]" for i in range(1, n + 1) for j in range(1, n + 1)}
            | {f"B[{i},{j}]" for i in range(1, n + 1) for j in (1, 2)}
            | {f"Q[{i}]" for i in range(1, n + 1)}
            | {f"h[{i}]:{cs.velocities[j]}*{cs.velocities[k]}"
               for i in range(1, n + 1) for j in range(n) for k in range(j, n)})
    assert set(truth) == want, set(truth) ^ want
    nu = red.nu
    for i in range(n):
        rebuilt = sum(truth[f"h[{i + 1}]:{nu[j]}*{nu[k]}"] * nu[j] * nu[k]
                      for j in range(n) for k in range(j, n))
        assert sp.expand(rebuilt - red.h[i]) == 0, i
    assert true_expressions("wip_platform", cs) is None
    with pytest.raises(UnknownNameError):
        true_expressions("no_such_model", cs)


def test_true_expressions_cold_cache_and_memory(tmp_path, monkeypatch):
    monkeypatch.setenv("WHEELED_DYN_CACHE", str(tmp_path))
    cs = builtin_coordinate_set(load_model("wip"), "seed001")
    start = time.perf_counter()
    first = true_expressions("wip", cs, refresh=True)
    elapsed = time.perf_counter() - start
    assert elapsed < FIRST_CALL_SECONDS, f"first call took {elapsed:.2f} s"
    assert list((tmp_path / "symbolic").glob("true-*.pickle")), "no disk entry written"
    assert true_expressions("wip", cs) is first  # memory
    wheeled_module._MEMORY.clear()
    again = true_expressions("wip", cs)           # disk
    assert again is not first and again == first


def test_cache_key_follows_coordinate_set_content():
    wm = load_model("wip")
    a = builtin_coordinate_set(wm, "seed001")
    b = builtin_coordinate_set(wm, "heading")    # same content, other name
    c = builtin_coordinate_set(wm, "wheels")
    key = wheeled_module.coordinate_set_key
    assert key(a) == key(b) and key(a) != key(c)


def test_errors():
    wm = load_model("wip")
    cs = builtin_coordinate_set(wm, "seed001")
    with pytest.raises(UnknownNameError):
        wheeled_symbolic(wm, cs, "nonsense")
    with pytest.raises(ModelError):
        wheeled_symbolic(load_model("wip_platform"),
                         builtin_coordinate_set(load_model("wip_platform"), "heading"))
    with pytest.raises(ModelError):
        wheeled_symbolic(wm, builtin_coordinate_set(wm, "full"), model_coordinates=True)


def test_element_expressions_of_a_multiplier_set_include_G():
    wm = load_model("wip")
    red = wheeled_symbolic(wm, builtin_coordinate_set(wm, "absolute_wheels"))
    out = element_expressions(red)
    assert "G[1,1]" in out and "G[4,5]" in out and "h[5]:dphi*dphi" in out


# -- CLI ------------------------------------------------------------------------------------
def _run(argv, capsys):
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers()
    symbolic_commands.add_commands(sub)
    args = parser.parse_args(argv)
    code = args.handler(args)
    return code, capsys.readouterr().out


def test_cli_text_latex_json(capsys):
    code, out = _run(["symbolic", "wip"], capsys)
    assert code == 0
    assert "A[1,1] = 2*I_a/R**2 + 2*Iw3/R**2 + 2*m_C + m_S" in out, out
    assert "Q[3] = -d*g*m_S*sin(phi) + d_x*g*m_S*cos(phi)" in out, out
    assert "B[2,1] = L/R" in out, out
    code, out = _run(["symbolic", "wip", "--latex"], capsys)
    assert code == 0 and out.startswith("A = \\left[") and "\\dot{\\psi}" in out
    code, out = _run(["symbolic", "wip", "--coords", "wheels", "--json"], capsys)
    data = json.loads(out)
    assert data["coordinates"] == ["dtheta_l", "dtheta_r", "dphi"]
    assert {"A", "C", "Q", "B", "h"} <= set(data)
    assert len(data["A"]) == 3 and len(data["h"]) == 3 and len(data["B"][0]) == 2
    assert all(isinstance(x, str) for row in data["C"] for x in row)


def test_closed_forms_are_keyed_by_which_lengths_are_drawn():
    r"""A model file whose ``[draw] fixed`` changed (one length kept instead of drawn, so a
    number where a symbol was) gets closed forms of its own: the key holds the lengths' table
    (before, only the numeric model and the named constants: the old forms were served)."""
    import dataclasses
    import types

    from wheeled_dyn.coordinates import builtin_coordinate_set
    from wheeled_dyn.models.registry import load_model
    from wheeled_dyn.symbolic.wheeled import _true_key
    wm = load_model("rolling_coin")
    table = wm.lengths
    name = next(iter(table.dimensions))
    dims = dict(table.dimensions)
    dims[name] = dataclasses.replace(dims[name], drawn=not dims[name].drawn)
    kept = dataclasses.replace(wm, lengths=dataclasses.replace(
        table, dimensions=types.MappingProxyType(dims)))
    cs = builtin_coordinate_set(wm)
    assert _true_key("rolling_coin", cs, wm) == _true_key("rolling_coin", cs, wm)
    assert _true_key("rolling_coin", cs, wm) != _true_key("rolling_coin", cs, kept)
