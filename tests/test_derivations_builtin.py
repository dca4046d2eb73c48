r"""The shipped derivation files of seed 001 load, have the right shapes, and keep what the
document printed (typos included) and what was reconstructed."""

from __future__ import annotations

import numpy as np
import pytest
import sympy

from wheeled_dyn.derivations import (KHALIL_FUNCTIONS, builtin_derivations, builtin_groups,
                                     builtin_tables, load_comparison_table, load_derivation,
                                     load_derivations)

SEED = 20261122
N_SAMPLES = 25
#: Largest |difference| accepted between two forms of the same table cell at random values.
NUMERIC_TOL = 1e-9

EXPECTED_FILES = {
    "eq25_lagrange", "kim_eq1_3", "kim_eq6_8", "report3_eq4_5", "appendix_kim_A_C",
    "book_eq9_11", "book_eq12_14", "sec5_nonholonomic",
}


def _by_name():
    return {p.stem: load_derivation(p) for p in builtin_derivations("seed001")}


def test_every_builtin_file_is_listed_and_loads():
    assert "seed001" in builtin_groups()
    paths = builtin_derivations("seed001")
    assert {p.stem for p in paths} == EXPECTED_FILES
    assert all(not p.name.endswith("_table.toml") for p in paths)
    loaded = load_derivations(paths)
    assert [d.path for d in loaded] == paths
    # a folder stands for its derivation files
    assert [d.path for d in load_derivations([paths[0].parent])] == paths


def test_shapes_of_every_builtin_file():
    for name, d in _by_name().items():
        n = d.n
        assert len(d.velocities) == len(d.accelerations) == n, name
        for key in ("A", "C"):
            M = getattr(d, key)
            if M is not None:
                assert M.shape == (n, n), (name, key)
        if d.Q is not None:
            assert d.Q.shape == (n, 1), name
        if d.B is not None:
            assert d.B.shape == (n, len(d.input_symbols)), name
        if d.G is not None:
            assert d.G.shape[1] == n, name
        if d.equations is not None:
            assert len(d.equations) == n, name
            terms = d.read_off()
            assert terms.A.shape == (n, n) and terms.h.shape == (n, 1), name
        assert d.form in ("matrices", "equations")
        # every input of the document drives some model input
        used = set().union(*(e.free_symbols for e in d.inputs.values())) if d.inputs else set()
        assert set(d.input_symbols) <= used, name


def test_every_symbol_has_a_model_value_or_says_why_not():
    for name, d in _by_name().items():
        for spec in d.symbols.values():
            assert (spec.value is not None) + spec.is_input + spec.free == 1, (name, spec.name)
            assert spec.units, (name, spec.name)


def test_eq25_as_printed_and_reconstructed():
    d = load_derivation(next(p for p in builtin_derivations() if p.stem == "eq25_lagrange"))
    s = d.symbol
    phi, dphi, dpsi = s("phi"), s("dphi"), s("dpsi")
    assert d.coordinates.use == "seed001"
    assert [str(q) for q in d.positions] == ["x", "psi", "phi"]
    # A12 has /R, A21 /R**2: kept as printed
    assert d.A[0, 1] == s("MZ1") - 2 * s("YZw") / s("R")
    assert d.A[1, 0] == s("MZ1") - 2 * s("YZw") / s("R") ** 2
    # the lost A33, restored and marked
    assert d.A[2, 2] == s("ZZ1")
    assert "A[3,3]" in d.reconstructed
    # C32 is printed with phi-dot
    XY1, XX1, YY1 = s("XY1"), s("XX1"), s("YY1")
    expected = -dphi / 2 * (2 * XY1 * sympy.cos(2 * phi) + (XX1 - YY1) * sympy.sin(2 * phi))
    assert sympy.simplify(d.C[2, 1] - expected) == 0
    assert not d.C[2, 1].has(dpsi)
    assert d.Q[2] == s("MX1") * s("g") * sympy.cos(phi) - s("MY1") * s("g") * sympy.sin(phi)
    assert d.B is None and d.missing == ()
    body = sympy.Symbol("body")
    assert d.symbols["XX1"].value == KHALIL_FUNCTIONS["XX"](body)


def test_kim_typos_kept():
    d = _by_name()["kim_eq1_3"]
    A, h, Q, B, inputs = d.read_off()
    s = d.symbol
    assert A[0, 0] == 3 * (s("m_c") + s("m_s"))
    # eq (3) has phi-dot**2 where the appendix finds psi-dot**2
    assert h[2].has(s("dphi")) and not h[2].has(s("dpsi"))
    assert B == sympy.Matrix([[-1 / s("R"), -1 / s("R")], [s("L") / s("R"), -s("L") / s("R")],
                              [1, 1]])
    assert [str(u) for u in inputs] == ["alpha3", "beta3"]


def test_report3_scale_and_assumptions():
    d = _by_name()["report3_eq4_5"]
    r = d.symbol("r")
    assert d.row_scale == (r, sympy.Integer(1))
    assert set(d.assumptions) == {"tau_f", "F_ext"}
    assert d.apply_assumptions(d.symbol("tau_f") + d.symbol("F_ext") + 1) == 1
    assert all(v == 0 for v in d.assumptions.values())
    full = d.read_off(assume=False)
    assert [str(u) for u in full.inputs] == ["u", "tau_f", "F_ext"]
    plain = d.read_off(unscale=True)
    assert sympy.simplify(plain.A[0, 0] - d.read_off().A[0, 0] / r) == 0
    assert d.coordinates.configuration["psi"] == 0
    assert d.coordinates.configuration["phi"] == -d.symbol("theta")


def test_appendix_and_sec5_reconstruction_marks():
    by = _by_name()
    app = by["appendix_kim_A_C"]
    assert app.A[2, 1] == 0 and "A[3,2]" in app.reconstructed
    assert app.Q is None and app.B is None
    sec5 = by["sec5_nonholonomic"]
    assert sec5.missing == tuple(f"C[5,{j}]" for j in range(1, 6))
    assert all(sec5.C[4, j] is sympy.nan for j in range(5))
    assert sec5.coordinates.rolling == "multipliers"
    assert sec5.G.shape == (2, 5)
    assert sec5.B == sympy.Matrix([[0, 0], [0, 0], [1, 0], [0, 1], [1, 1]])


def test_sec5_definitions_expanded():
    d = _by_name()["sec5_nonholonomic"]
    s = d.symbol
    psi = s("R") / s("L") * (s("theta_l") - s("theta_r"))
    assert sympy.simplify(d.definitions["psi"] - psi) == 0
    # no abbreviation survives in the matrices
    abbreviations = {s(n) for n in ("Mbb", "Ibb", "Nbb", "Sbb1", "Sbb2", "Zbb", "psi", "dpsi")}
    for M in (d.A, d.C, d.Q, d.G):
        assert not (M.free_symbols & abbreviations)
    Mbb = 2 * s("I_w3") / s("R") ** 2 + 2 * s("m_C") + s("m_S")
    assert sympy.simplify(d.A[0, 0] - Mbb * sympy.cos(psi) ** 2) == 0
    # constraint (33) as printed: sin/cos in the second row, unlike G's second row
    G33 = d.constraint_matrix()
    assert G33[1, 0] == sympy.sin(psi) and d.G[1, 0] == sympy.cos(psi)
    assert G33[1, 2] == -s("R") / 2


def test_seed_table_loads_and_is_self_consistent():
    (path,) = builtin_tables("seed001")
    t = load_comparison_table(path)
    assert len(t.entries) == 18
    assert t.mismatched == ("A22", "C12", "C22", "C23", "C32")
    assert set(t.differences) == {"equation 1", "equation 2", "equation 3"}
    rng = np.random.default_rng(SEED)
    names = sorted(t.namespace.values(), key=str)
    differing = set()
    for e in t.entries:
        gap = e.derived.xreplace(dict(t.substitution)) - e.equivalent[-1]
        f = sympy.lambdify(names, gap, "numpy")
        worst = max(abs(f(*rng.uniform(0.1, 2.0, len(names)))) for _ in range(N_SAMPLES))
        if worst > NUMERIC_TOL:
            differing.add(e.name)
    # the printed A22 'equivalent form' has I_w2 where I_w3 belongs: the only cell that
    # does not follow from its derived expression by the printed substitution
    assert differing == {"A22"}
    A = t.matrix("A", "derived")
    eq25 = _by_name()["eq25_lagrange"]
    assert A[2, 2] == t.namespace["ZZ1"] and A.shape == eq25.A.shape


def test_value_names_exist_in_the_models():
    r"""Cross-check against the model code: every value expression of the shipped files names
    parameters and links the model has (the parser itself does not import the models)."""
    import dataclasses

    wip_parameters = pytest.importorskip("wheeled_dyn.models.wip_parameters")
    physical = {f.name for f in dataclasses.fields(wip_parameters.WipParameters)}
    names = {
        "wip": (physical | {"R", "L", "g"}, {"body", "wheel_left", "wheel_right"}),
        "wip_platform": ({"R", "L", "g"}, {"platform", "pendulum", "wheel_left", "wheel_right"}),
    }
    paths = builtin_derivations("seed001")
    for path in paths:
        model = load_derivation(path).model
        parameters, links = names[model]
        d = load_derivation(path, parameters=parameters, links=links)
        assert d.model == model
