r"""The truth in the document's own symbols and the corrected equations (issue 26, item 4).

Three independent checks:

- a term planted out of a derivation comes back, in the file's symbols, as truth − document
  (the ROS balancer without the wheels' spin inertia :math:`2J_w/R^2` in :math:`A_{11}`,
  the free block of seed 000 7.2 without :math:`(I_1 - I_3)pr/I_2` in its q-equation);
- the corrected equation, written back into the derivation in place of the wrong one, makes
  the document right: the comparison (Pinocchio's numbers, not the closed forms the correction
  is written from) then finds the whole system equivalent;
- the corrected LaTeX is valid LaTeX for the report's renderer (latex2mathml).
"""

from __future__ import annotations

from pathlib import Path

import latex2mathml.converter
import pytest
import sympy as sp

from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation

ROS = Path(__file__).parent / "data" / "ros_balancer"
SHIPPED = Path(__file__).parents[1] / "src" / "wheeled_dyn" / "data" / "derivations"
SEED = 2026


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED)


def test_dropped_wheel_inertia_reads_in_the_files_symbols(engine):
    result = engine.compare(load_derivation(ROS / "ros_balancer_dropped_wheel.toml"))
    assert result.truth_in_document
    records = {r.element: r for r in result.records}
    wrong = [e for e, r in records.items() if r.verdict == Verdict.DIFFERS]
    assert wrong == ["A[1,1]"]
    J_w, R = sp.Symbol("J_w", real=True), sp.Symbol("R", real=True)     # R: drawn, a symbol
    residual = sp.sympify(records["A[1,1]"].residual, locals={"J_w": J_w, "R": R})
    assert sp.simplify(residual - 2 * J_w / R**2) == 0
    truth = records["A[1,1]"].truth
    assert "M_" not in truth and "YY_" not in truth          # no model parameter left
    eq = result.equations[0]
    assert eq.verdict == Verdict.DIFFERS and eq.corrected and eq.corrected_latex
    assert all(not e.corrected for e in result.equations[1:])
    latex2mathml.converter.convert(eq.corrected_latex)


def _equations_file(path: Path, tmp: Path, rows: list[str]) -> Path:
    r"""The derivation ``path`` with its matrices replaced by the equations ``rows``."""
    text = path.read_text()
    head = text[:text.index("[matrices]")]
    body = "[matrices]\nequations = [\n" + ",\n".join(f'  "{r}"' for r in rows) + "\n]\n"
    out = tmp / path.name
    out.write_text(head.replace('model = "ros_balancer.toml"',
                                f'model = "{ROS / "ros_balancer.toml"}"') + body)
    return out


def test_the_corrected_equation_makes_the_document_right(engine, tmp_path):
    r"""Equation 1 as corrected, with the file's equations 2 and 3 written out from its own
    matrices (:math:`A\dot\nu + C\nu + Q = Bu`): Pinocchio's truth finds them equivalent."""
    path = ROS / "ros_balancer_dropped_wheel.toml"
    d = load_derivation(path)
    result = engine.compare(d)
    terms = d.read_off()
    lhs = terms.A * sp.Matrix(d.accelerations) + terms.h + terms.Q
    rhs = terms.B * sp.Matrix(terms.inputs)
    rows = [result.equations[0].corrected] + [
        f"{sp.sstr(lhs[i])} = {sp.sstr(rhs[i])}" for i in (1, 2)]
    again = engine.compare(load_derivation(_equations_file(path, tmp_path, rows)))
    assert again.equivalent is True, [(e.label, e.verdict, e.texts) for e in again.equations]


def test_a_free_body_missing_its_gyroscopic_term(engine, tmp_path):
    r"""Seed 000 7.2's free block (a free base, body rates p, q, r) with the q-equation's
    :math:`(I_1 - I_3)pr/I_2` dropped: truth − document names it in the file's symbols, and
    the corrected equation, in the file's frame (divided by :math:`I_2`), restores it."""
    source = SHIPPED / "seed000" / "p7_2_euler_equations.toml"
    text = source.read_text().replace("[0, 0, 0, 0, 0, (I1 - I3)*p/I2]", "[0, 0, 0, 0, 0, 0]")
    assert text != source.read_text()
    path = tmp_path / "dropped.toml"
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    assert result.truth_in_document
    records = {r.element: r for r in result.records}
    I1, I2, I3, p, r = sp.symbols("I1 I2 I3 p r", real=True)
    names = {"I1": I1, "I2": I2, "I3": I3, "p": p, "r": r}
    h = records["h[5]:p*r"]
    assert h.verdict == Verdict.DIFFERS
    assert sp.simplify(sp.sympify(h.residual, locals=names) - (I1 - I3) / I2) == 0
    eq = next(e for e in result.equations if e.index == 4)
    assert eq.corrected
    lhs, rhs = eq.corrected.split(" = ")
    dq = sp.Symbol("dq", real=True)
    written = sp.sympify(lhs, locals=names | {"dq": dq}) - sp.sympify(rhs, locals=names)
    assert sp.simplify(written - (dq + (I1 - I3) * p * r / I2)) == 0
    latex2mathml.converter.convert(eq.corrected_latex)


def test_a_symbol_no_parameter_is_solved_from_reads_in_the_truths_symbols(engine, tmp_path):
    r"""A second wheel mass ``m_w2 = M(right_wheel)``: the parameter sets keep the two wheels
    alike, so nothing is solved from it (``m_w`` gave the mass already). The document's side is
    read with ``m_w2`` as ``m_w``, and A[1,1] written ``m_b + m_w + m_w2`` leaves exactly the
    dropped :math:`2J_w/R^2`, with no spurious ``m_w - m_w2``."""
    text = (ROS / "ros_balancer_dropped_wheel.toml").read_text()
    text = text.replace('model = "ros_balancer.toml"', f'model = "{ROS / "ros_balancer.toml"}"')
    text = text.replace("  [m_b + 2*m_w,", "  [m_b + m_w + m_w2,")
    text = text.replace('J_w  = { value = "IYY(left_wheel)"',
                        'm_w2 = { value = "M(right_wheel)", units = "kg" }\n'
                        'J_w  = { value = "IYY(left_wheel)"')
    path = tmp_path / "two_wheel_masses.toml"
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    records = {r.element: r for r in result.records}
    assert [e for e, r in records.items() if r.verdict == Verdict.DIFFERS] == ["A[1,1]"]
    J_w, R = sp.Symbol("J_w", real=True), sp.Symbol("R", real=True)
    residual = sp.sympify(records["A[1,1]"].residual, locals={"J_w": J_w, "R": R})
    assert sp.simplify(residual - 2 * J_w / R**2) == 0, residual


def test_document_symbols_named_as_other_model_parameters_stay_apart(engine, tmp_path):
    r"""The planar robot of ``examples/`` with its wheel radius named ``d`` (the model's
    ``R``) and its axle-to-centre distance named ``R`` (the model's ``d``), the wheels' spin
    inertia 2 J_w/d² dropped from A₁₁: truth − document is that term in the file's own
    symbols, and the pitch inertia reads J_b + m_b R² — the names the file gives, never the
    model's quantities of the same names (the truth was printed with one for the other)."""
    import re
    text = (Path(__file__).parents[1] / "examples" / "my_planar_robot.toml").read_text()
    head, body = text.split("[symbols]")
    body = re.sub(r"\br\b", "d", re.sub(r"\bl\b", "R", body))
    body = body.replace(" + 2*J_w/d**2", "", 1)
    path = tmp_path / "clash.toml"
    path.write_text(head + "[symbols]" + body)
    result = engine.compare(load_derivation(path))
    records = {r.element: r for r in result.records}
    names = {n: sp.Symbol(n, real=True) for n in ("J_w", "J_b", "m_b", "d", "R")}
    residual = sp.sympify(records["A[1,1]"].residual, locals=names)
    assert sp.simplify(residual - 2 * names["J_w"] / names["d"] ** 2) == 0, residual
    truth = sp.sympify(records["A[2,2]"].truth, locals=names)
    assert sp.simplify(truth - names["J_b"] - names["m_b"] * names["R"] ** 2) == 0, truth
