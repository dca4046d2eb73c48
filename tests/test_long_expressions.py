"""A form solved for the accelerations and never simplified: its elements run to tens of
thousands of operations once read off (the planar elbow manipulator of ``published_forms.py``,
:math:`\\ddot q_2` substituted into :math:`\\ddot q_1` as a probe wrote it: 45 000 in one
element). Every trial reading of such an element was compiled (half a minute for the file)
and its LaTeX typeset as MathML (seconds each). Above :data:`~wheeled_dyn.compare.judge.element.
TRIAL_OPS` an element is tried only for a symbol read as another everywhere (nothing
compiled); LaTeX above :data:`~wheeled_dyn.report.html_text.MATHML_LIMIT` characters is shown
as its beginning. The verdicts are those of the numbers, as for any element."""

from __future__ import annotations

import pytest
import sympy as sp

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge import element
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.report.html_text import MATHML_LIMIT, mathml

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3


def _nested(folder, error: str | None):
    r"""The arm solved as ``ddq2 = ...`` (from the second equation with q̈₁ eliminated),
    then ``ddq1`` with that expression substituted, nothing simplified."""
    D, c, phi = P.arm(error)
    tau = sp.Matrix([P.tau1, P.tau2])
    r = tau - c - phi
    ddq2 = (r[1] - D[0, 1] * r[0] / D[0, 0]) / (D[1, 1] - D[0, 1] ** 2 / D[0, 0])
    ddq1 = (r[0] - D[0, 1] * ddq2) / D[0, 0]
    rows = [f"ddq2 = {P._s(ddq2)}", f"ddq1 = {P._s(ddq1)}"]
    path = folder / f"nested_{error or 'right'}.toml"
    path.write_text(P.ARM_HEAD.format(form="nested", error=f", {error}" if error else "",
                                      model=P.DATA / "two_link_arm.toml",
                                      eqs=",\n".join(f'  "{e}"' for e in rows)))
    return load_derivation(path)


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def test_the_nested_solved_form_agrees(engine, tmp_path):
    result = engine.compare(_nested(tmp_path, None))
    assert all(r.verdict == Verdict.AGREES for r in result.records)


def test_a_long_element_is_not_read_with_compiled_changes(engine, tmp_path, monkeypatch):
    def refuse(name):
        original = getattr(element, name)

        def guarded(expr, *args, **kwargs):
            assert sp.count_ops(expr) <= element.TRIAL_OPS, f"{name} on a long element"
            return original(expr, *args, **kwargs)
        monkeypatch.setattr(element, name, guarded)
    for name in ("element_term_diagnoses", "product_swaps", "product_diagnoses"):
        refuse(name)
    d = _nested(tmp_path, "swap")
    result = engine.compare(d)
    differing = [r for r in result.records if r.verdict == Verdict.DIFFERS]
    assert differing and not result.equivalent
    terms = d.read_off(assume=True, unscale=False)
    longest = max(sp.count_ops(x) for x in (*terms.Q, *terms.h))
    assert longest > element.TRIAL_OPS        # the case exercises the limit


def test_long_latex_is_shown_as_its_beginning():
    long = "x + " * (MATHML_LIMIT // 4 + 10) + "y"
    shown = mathml(long)
    assert "not typeset" in shown and str(len(long)) in shown
    assert len(shown) < MATHML_LIMIT // 5
    assert mathml(r"\frac{a}{b}").startswith("<math")
