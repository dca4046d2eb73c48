"""A row solved for its accelerations is shown beside the truth in the same frame.

A form solved for the accelerations, :math:`\\ddot q = D^{-1}(\\tau - c - \\phi)`, is compared
in the frame of row :math:`i` of the true :math:`A^{-1}`. The reports showed, beside each of
its elements, the truth of the equations *before* solving (the acrobot's gravity term
:math:`\\phi_1` beside the document's :math:`(D^{-1}\\phi)_1`: a probe), and no truth − document.
The truth is now written in that frame where the closed forms and the declarations give it:
here checked against the planar elbow manipulator's own equations (Spong, Hutchinson and
Vidyasagar, *Robot Modeling and Control*, section 7.4; ``published_forms.py``) solved by
SymPy independently, at random values of the symbols.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation

#: Engine grid; random points of the symbols; relative agreement of two expressions there.
SAMPLES, PARAM_SETS, POINTS, TOL = 200, 3, 3, 1e-9


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _equal(a: sp.Expr, b: sp.Expr) -> bool:
    names = sorted(a.free_symbols | b.free_symbols, key=str)
    rng = np.random.default_rng(SEED)
    for _ in range(POINTS):
        point = dict(zip(names, rng.uniform(0.3, 1.3, len(names))))
        va, vb = (complex(x.evalf(subs=point)) for x in (a, b))
        if abs(va - vb) > TOL * max(abs(va), abs(vb), 1.0):
            return False
    return True


def _symbols(text: str) -> sp.Expr:
    names = {s.name: s for s in (P.q1, P.q2, P.m1, P.m2, P.l1, P.lc1, P.lc2, P.I1, P.I2, P.g)}
    return sp.sympify(text, locals=names)


def test_the_solved_rows_truth_is_that_of_the_solved_equations(engine, tmp_path):
    result = engine.compare(load_derivation(P.write(tmp_path, "arm", "solved", None)))
    D, _, phi = P.arm()
    gravity = D.inv() * phi                           # q̈ = D⁻¹(τ − c − φ): n holds D⁻¹φ
    shown = {r.element: r.truth for r in result.records}
    assert all(r.verdict == Verdict.AGREES for r in result.records)
    for i in range(2):
        assert _equal(_symbols(shown[f"Q[{i + 1}]"]), gravity[i])
        for j in range(2):
            assert _equal(_symbols(shown[f"A[{i + 1},{j + 1}]"]), sp.Integer(int(i == j)))


def test_a_term_dropped_from_one_solved_row_gets_its_truth_minus_document(engine, tmp_path):
    r"""The solved form written as an author prints it, :math:`\ddot q_1 = (d_{22}(\tau_1 -
    c_1 - \phi_1) - d_{12}(\tau_2 - c_2 - \phi_2))/\det D`, with :math:`\phi_1` dropped
    from the first row only (the probe's acrobot case): its gravity element differs and
    truth − document is what the document lacks, :math:`d_{22}\phi_1/\det D` (SymPy's
    own, from the textbook's D and φ)."""
    D, c, phi = P.arm()
    det = D[0, 0] * D[1, 1] - D[0, 1] ** 2
    s = P._s
    rows = [f"ddq1 = (({s(D[1, 1])})*(tau1 - ({s(c[0])})) - ({s(D[0, 1])})*(tau2 - ({s(c[1])})"
            f" - ({s(phi[1])})))/({s(det)})",
            f"ddq2 = (({s(D[0, 0])})*(tau2 - ({s(c[1])}) - ({s(phi[1])})) - ({s(D[0, 1])})"
            f"*(tau1 - ({s(c[0])}) - ({s(phi[0])})))/({s(det)})"]
    path = tmp_path / "arm_solved_phi1_dropped.toml"
    path.write_text(P.ARM_HEAD.format(form="solved", error=", phi1 dropped from row 1",
                                      model=P.DATA / "two_link_arm.toml",
                                      eqs=",\n".join(f'  "{e}"' for e in rows)))
    result = engine.compare(load_derivation(path))
    differing = {r.element: r for r in result.records if r.verdict == Verdict.DIFFERS}
    assert set(differing) == {"Q[1]"}
    residual = differing["Q[1]"].residual
    assert residual
    assert _equal(_symbols(residual), D[1, 1] * phi[0] / det)


def _barto(folder, sign: int):
    r"""The cart-pole as Barto, Sutton and Anderson's simulation computes it (IEEE Trans. SMC
    13, 1983; Florian 2007, eqs. (21)–(22) without friction), :math:`\ddot\theta` first —
    the order of that code, not of the positions (x, θ) — and :math:`\ddot x` from it;
    ``sign`` −1 flips the sign of :math:`\cos\theta\,T` in :math:`\ddot\theta` (a probe's
    planted error)."""
    T = "(F + m*l*dtheta**2*sin(theta))/(M + m)"
    rows = [f"ddtheta = (g*sin(theta) - ({sign})*cos(theta)*{T})"
            "/(l*(4/3 - m*cos(theta)**2/(M + m)))",
            "ddx = (F + m*l*(dtheta**2*sin(theta) - ddtheta*cos(theta)))/(M + m)"]
    path = folder / f"barto_{sign}.toml"
    path.write_text(P.POLE_HEAD.format(form="Barto's simulation", error="",
                                       model=P.DATA / "cart_pole.toml",
                                       eqs=",\n".join(f'  "{e}"' for e in rows)))
    return load_derivation(path)


def test_a_row_solved_for_another_coordinate_is_read_as_solved(engine, tmp_path):
    r"""θ̈ printed first, for positions (x, θ): its row is :math:`e_2`, a row of
    :math:`A^{-1}` all the same. It was explained as the cart's equation divided by
    :math:`m l \cos\theta` (which vanishes), with four unrelated diagnoses for one sign; read
    as solved, the sign is named where it is."""
    right = engine.compare(_barto(tmp_path, 1))
    assert all(r.verdict == Verdict.AGREES for r in right.records)
    assert "solved for the accelerations" in right.equations[0].frame
    wrong = engine.compare(_barto(tmp_path, -1))
    differing = [r for r in wrong.records if r.verdict == Verdict.DIFFERS]
    assert {r.element for r in differing} == {"B[1,1]", "h[1]:dtheta*dtheta"}
    assert all(any(x.kind == K.SIGN for x in r.diagnoses) for r in differing)
