r"""A slender rod hung from a Cardan (gimbal) joint (``data/spherical_pendulum``, written for
the tests): its axial inertia is zero, so the true mass matrix diag(J cos²b, J) is singular at
the special position b = ±π/2, where the first true equation vanishes as a whole; and the
same rod in spherical angles through a map of atan2 and asin, for which no closed forms are
derived (their simplification did not end).

The equations are Lagrange's for :math:`T = \tfrac J2(\cos^2 b\,\dot a^2 + \dot b^2)`,
:math:`V = -mgl_c\cos a\cos b`, and for :math:`T = \tfrac J2(\dot\theta^2 + \sin^2\theta\,
\dot\varphi^2)`, :math:`V = -mgl_c\cos\theta` (J. B. Marion, S. T. Thornton, *Classical
Dynamics of Particles and Systems*, the spherical pendulum, with :math:`J = I + ml_c^2` of a
rod for :math:`ml^2`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from shipped_copies import rewritten_copy
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.grid.grid import derivation_coordinate_set
from wheeled_dyn.compare.grid.samples import parameter_sets
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.symbolic.simplify import TRIGSIMP_OPS, simplify_expr
from wheeled_dyn.symbolic.wheeled import trig_polynomial_map, true_expressions

DATA = Path(__file__).parent / "data" / "spherical_pendulum"
GIMBAL, SPHERICAL = DATA / "gimbal_equations.toml", DATA / "spherical_atan2.toml"
SAMPLES, PARAM_SETS = 1000, 5


def _copy(tmp_path: Path, source: Path, *replacements: tuple[str, str]) -> Path:
    for name in ("spherical_pendulum.toml", "spherical_pendulum.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    return rewritten_copy(source, tmp_path, *replacements)


def _compare(path: Path):
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS).compare(
        load_derivation(path))


@pytest.mark.parametrize("source", [GIMBAL, SPHERICAL], ids=["gimbal", "spherical"])
def test_the_right_equations_agree(source: Path) -> None:
    r"""Every element agrees and the system is right: at b = ±π/2 the truth loses its first
    equation as the document does (it was "equation 1 is not independent ... at a special
    position", the truth's own singularity blamed on the document); the spherical map's
    numbers are compared without closed forms."""
    result = _compare(source)
    assert result.equivalent is True, [t for e in result.equations for t in e.texts]
    assert all(r.verdict == "agrees" for r in result.records), \
        {r.element: r.texts for r in result.records if r.verdict != "agrees"}
    assert not result.asymmetric


@pytest.mark.parametrize("source, old, new, element", [
    (GIMBAL, "m*g*lc*sin(a)*cos(b) = 0", "m*g*lc*sin(a) = 0", "Q[1]"),
    (GIMBAL, "+ (I + m*lc**2)*cos(b)*sin(b)*da**2", "- (I + m*lc**2)*cos(b)*sin(b)*da**2",
     "h[2]:da*da"),
    (SPHERICAL, "- (I + m*lc**2)*sin(th)*cos(th)*dph**2", "+ (I + m*lc**2)*sin(th)*cos(th)*dph**2",
     "h[1]:dph*dph"),
], ids=["gimbal-cos-dropped", "gimbal-sign", "spherical-sign"])
def test_a_planted_error_differs(tmp_path: Path, source: Path, old: str, new: str,
                                 element: str) -> None:
    result = _compare(_copy(tmp_path, source, (old, new)))
    assert result.equivalent is False
    assert {r.element for r in result.records if r.verdict == "differs"} == {element}


E1 = ('"(I + m*lc**2)*cos(b)**2*dda - 2*(I + m*lc**2)*cos(b)*sin(b)*da*db + '
      'm*g*lc*sin(a)*cos(b) = 0"')
E2 = '"(I + m*lc**2)*ddb + (I + m*lc**2)*cos(b)*sin(b)*da**2 + m*g*lc*cos(a)*sin(b) = 0"'


def _times(equation: str, factor: str) -> str:
    lhs = equation[1:-len(' = 0"')]
    return f'"{factor}*({lhs}) = 0"'


@pytest.mark.parametrize("rows, lost", [
    ((E1, _times(E2, "cos(b)")), 1),
    ((E1, _times(E2, "cos(b)**2")), 1),
    ((E1[:-len(' = 0"')] + ' + cos(b)**2*(' + E2[1:-len(' = 0"')] + ') = 0"',
      _times(E2, "cos(b)**2")), 1),
    ((_times(E1, "cos(b)**2"), _times(E2, "cos(b)**2")), 1),
], ids=["E2-cos", "E2-cos2", "E1+cos2E2-cos2E2", "both-cos2"])
def test_an_equation_lost_where_the_truth_keeps_it(tmp_path: Path, rows: tuple[str, str],
                                                   lost: int) -> None:
    r"""The second equation times cos b or cos²b (alone, or also in a combination with the
    first): lost at b = ±π/2, where the true second row does not vanish (only the first does).
    Those states were left out whole once the truth's own vanishing row was: cos²b, which
    keeps its sign, was then "right as a system"."""
    path = _copy(tmp_path, GIMBAL, (E1, rows[0]), (E2, rows[1]))
    result = _compare(path)
    assert result.equivalent is False
    assert result.equations[lost].verdict == "differs", \
        [t for e in result.equations for t in e.texts]


def test_the_first_equation_times_cos2_b_is_not_lost(tmp_path: Path) -> None:
    r"""The first equation times cos²b: lost at b = ±π/2 only where the true first equation
    is lost too (its every term holds cos b): right as a system."""
    result = _compare(_copy(tmp_path, GIMBAL, (E1, _times(E1, "cos(b)**2"))))
    assert result.equivalent is True, [t for e in result.equations for t in e.texts]


def test_no_closed_forms_through_inverse_sines() -> None:
    d = load_derivation(SPHERICAL)
    sets = parameter_sets(d.model, 1, np.random.default_rng(0))
    cs = derivation_coordinate_set(d, sets[0])
    assert not trig_polynomial_map(cs)
    assert true_expressions(d.model, cs) is None
    gimbal = load_derivation(GIMBAL)
    assert trig_polynomial_map(derivation_coordinate_set(gimbal, sets[0]))


def test_trigsimp_only_on_short_expressions() -> None:
    r"""A quotient that is no polynomial in sines and cosines is simplified by ``trigsimp``
    where it is short, and left as it is above :data:`TRIGSIMP_OPS` operations."""
    x, y = sp.symbols("x y", real=True)
    short = (sp.sin(x) ** 2 + sp.cos(x) ** 2) / (1 + y ** 2)
    assert simplify_expr(short) == 1 / (y ** 2 + 1)
    long = sum(sp.sin(k * x + y) ** 2 / (k + sp.cos(x) ** 2) for k in range(1, 40))
    assert sp.count_ops(long) > TRIGSIMP_OPS
    assert simplify_expr(long) == long


def test_rows_that_become_one_where_the_truth_loses_another_are_lost() -> None:
    r"""Three equations at a state where the true first row vanishes (the truth of rank 2
    there): a document whose second and third rows become one there, though none of them
    vanishes, loses an equation the truth keeps — its second and third are named, not the
    first (lost in the truth too); a document of the truth's rank there loses none."""
    from wheeled_dyn.compare.judge.lost_at import vanishing_at
    rng = np.random.default_rng(5)
    X = rng.normal(size=(20, 3, 3))
    true = X @ np.swapaxes(X, 1, 2) + 3 * np.eye(3)
    true[0] = np.diag([0.0, 1.0, 2.0])
    doc = true.copy()
    doc[0] = [[0.0, 0.0, 0.0], [0.0, 1.0, 2.0], [0.0, 1.0, 2.0]]
    assert vanishing_at(doc, true) == (1, 2)
    doc[0] = [[0.0, 0.0, 0.0], [0.0, 1.0, 2.0], [0.0, 1.0, -2.0]]
    assert vanishing_at(doc, true) is None
