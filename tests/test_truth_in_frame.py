r"""The truth a report shows for an element is the one it was compared with — the true
equations in the row's frame — so that truth − document is the difference of the two cells.

The two-link arm of ``tests/data/two_link_arm/arm_lagrange.toml`` (two uniform rods; Spong,
Hutchinson & Vidyasagar, *Robot Modeling and Control*, §7.3) with its first equation replaced
by the first minus the second (the first step of solving them), once right and once with the
second equation's gravity term not subtracted: the row is compared with eq1 − eq2; the
document's extra term m2 g l2/2 cos(q1 + q2) — a sine or cosine of a sum of the positions the
document writes — is named as a term it has too many, and the truth cell is eq1 − eq2's."""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

from wheeled_dyn.compare import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation

from conftest import SEED

ARM = Path(__file__).parent / "data" / "two_link_arm" / "arm_lagrange.toml"
#: Small grid.
SAMPLES, PARAM_SETS = 200, 2

EQ1 = ("(m1*l1**2/3 + m2*(l1**2 + l2**2/3 + l1*l2*cos(q2)))*ddq1 + m2*(l2**2/3 + l1*l2*cos(q2)/2)"
       "*ddq2 - m2*l1*l2/2*sin(q2)*(2*dq1*dq2 + dq2**2) + (m1/2 + m2)*g*l1*cos(q1) + m2*g*l2/2"
       "*cos(q1 + q2) = tau1")
#: eq1 − eq2, as a user writes it out (the gravity of the forearm cancels).
COMBINED = ("(m1*l1**2/3 + m2*(l1**2 + l1*l2*cos(q2)/2))*ddq1 + m2*l1*l2*cos(q2)/2*ddq2"
            " - m2*l1*l2/2*sin(q2)*(2*dq1*dq2 + dq2**2) - m2*l1*l2/2*sin(q2)*dq1**2"
            " + (m1/2 + m2)*g*l1*cos(q1){extra} = tau1 - tau2")


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _records(engine, tmp_path, extra: str):
    text = ARM.read_text()
    assert EQ1 in text
    path = tmp_path / "arm.toml"
    path.write_text(text.replace(EQ1, COMBINED.format(extra=extra)).replace(
        'model = "two_link_arm.toml"', f'model = "{ARM.parent / "two_link_arm.toml"}"'))
    return {r.element: r for r in engine.compare(load_derivation(path)).records}


def test_the_combined_row_agrees_and_shows_the_combined_truth(engine, tmp_path):
    records = _records(engine, tmp_path, "")
    assert all(r.verdict == Verdict.AGREES for r in records.values())
    m1, m2, l1, g, q1 = sp.symbols("m1 m2 l1 g q1")
    assert sp.simplify(sp.sympify(records["Q[1]"].truth) - (m1 / 2 + m2) * g * l1 * sp.cos(q1)) \
        == 0


def test_a_term_not_subtracted_is_named_with_the_truth_it_is_compared_with(engine, tmp_path):
    records = _records(engine, tmp_path, " + m2*g*l2/2*cos(q1 + q2)")
    q = records["Q[1]"]
    assert q.verdict == Verdict.DIFFERS
    others = [r for e, r in records.items() if e != "Q[1]"]
    assert all(r.verdict == Verdict.AGREES for r in others)
    (extra,) = [d for d in q.diagnoses if d.kind == K.EXTRA]
    m2, l2, g, q1, q2 = sp.symbols("m2 l2 g q1 q2")
    # the term named as the document has it too much (its sign as written)
    assert sp.simplify(sp.sympify(extra.terms[0]) - m2 * g * l2 / 2 * sp.cos(q1 + q2)) == 0
    truth, document, residual = (sp.sympify(x) for x in (q.truth, q.document, q.residual))
    assert sp.simplify(truth - document - residual) == 0
