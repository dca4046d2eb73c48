r"""A uniform body's formula written for a body's own moment the model's body does not follow
(:func:`wheeled_dyn.compare.judge.own_inertia.formula_reading`): the ROS balancer's Kane
equations in heading coordinates (``data/ros_balancer/ros_balancer_heading.toml``) with its
wheels' spin inertia written as a uniform disc's, :math:`J_w = m_w R^2/2` — in A[1,1]
:math:`m_b + 2m_w + 2J_w/R^2` becomes :math:`m_b + 3m_w`, in A[2,2]
:math:`2m_wL^2 + 2J_wL^2/R^2` becomes :math:`3m_wL^2` — on a URDF whose wheels are no uniform
discs (IYY 0.003 where :math:`mR^2/2` = 0.004). Each differing element names the part of the
written term that stands where the wheels' own moment belongs (it was only "truth −
document = 2*J_w/R**2 - m_w"). On the shipped URDF (uniform discs) the same file agrees only
if the wheel is a uniform body, and says no more; a typo in the written term and a dropped
term are not read so."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "ros_balancer"
A11, A22 = "m_b + 2*m_w + 2*J_w/R**2", "2*m_w*L**2 + 2*J_w*L**2/R**2"


def _compare(folder: Path, uniform_urdf: bool, a11: str, a22: str = A22):
    urdf = (DATA / "ros_balancer.urdf").read_text()
    if not uniform_urdf:
        assert urdf.count('iyy="0.004"') == 2
        urdf = urdf.replace('iyy="0.004"', 'iyy="0.003"')
    (folder / "ros_balancer.urdf").write_text(urdf)
    (folder / "ros_balancer.toml").write_text((DATA / "ros_balancer.toml").read_text())
    text = (DATA / "ros_balancer_heading.toml").read_text()
    assert text.count(A11) == 1 and text.count(A22) == 1
    path = folder / "doc.toml"
    path.write_text(text.replace(A11, a11).replace(A22, a22))
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(load_derivation(path))


def _formula(record) -> list:
    return [x for x in record.diagnoses if x.kind == DiagnosisKind.SWAP
            and "a formula for it (as for a uniform body)" in x.text]


def test_the_disc_formula_is_named_where_the_wheels_are_no_discs(tmp_path):
    result = _compare(tmp_path, False, "m_b + 3*m_w", "3*m_w*L**2")
    assert result.equivalent is False
    by = {r.element: r for r in result.records}
    (one,) = _formula(by["A[1,1]"])
    assert (one.written, one.term, one.fits) == (
        "m_w", "3*m_w", "Iyy(left_wheel) + Iyy(right_wheel) × R**(-2)"), one
    (two,) = _formula(by["A[2,2]"])
    assert two.written == "L**2*m_w" and two.fits.endswith("× L**2/R**2"), two
    said = " ".join(c.explanation for c in result.causes if c.kind == CauseKind.SWAP)
    assert "the document writes m_w (of its 3*m_w) where the moment of inertia " \
        "Iyy(left_wheel) + Iyy(right_wheel) about its own centre of mass × R**(-2) " \
        "(2*J_w/R**2 in the document's symbols) fits" in said      # J_w: as the file declares it


def test_on_uniform_wheels_the_formula_agrees_only_if_and_is_not_named(tmp_path):
    result = _compare(tmp_path, True, "m_b + 3*m_w", "3*m_w*L**2")
    by = {r.element: r for r in result.records}
    assert by["A[1,1]"].verdict == "agrees_if" and not _formula(by["A[1,1]"])


@pytest.mark.parametrize("a11", ["m_b + 4*m_w + 2*J_w/R**2", "2*m_w + 2*J_w/R**2"],
                         ids=["typo-in-the-term", "body-mass-dropped"])
def test_other_errors_are_no_formula(tmp_path, a11):
    result = _compare(tmp_path, False, a11)
    by = {r.element: r for r in result.records}
    assert by["A[1,1]"].verdict == "differs" and not _formula(by["A[1,1]"]), \
        by["A[1,1]"].diagnoses
    assert by["A[2,2]"].verdict == "agrees"


@pytest.mark.parametrize("uniform_urdf", [False, True], ids=["no-discs", "discs"])
def test_the_disc_formula_before_solving_is_named_in_the_inertia_read_back(tmp_path,
                                                                         uniform_urdf):
    r"""The same formula in the balancer's equations solved by Cramer's rule
    (:func:`balancer_solved.balancer_solved`, M11 = m_b + 3 m_w): the inertia read back
    from the solved equations names it in A[1,1] (it was "A[1,1] differs"); on wheels that
    are discs the solved equations agree only if the wheel is uniform, and the formula is no
    error there."""
    from balancer_solved import balancer_solved
    path = balancer_solved(tmp_path, A11.replace("m_b + 2*m_w + 2*J_w/R**2",
                                                 "2*J_w/R**2 + m_b + 2*m_w"), "m_b + 3*m_w")
    urdf = (DATA / "ros_balancer.urdf").read_text()
    (tmp_path / "ros_balancer.urdf").write_text(
        urdf if uniform_urdf else urdf.replace('iyy="0.004"', 'iyy="0.003"'))
    (tmp_path / "ros_balancer.toml").write_text((DATA / "ros_balancer.toml").read_text())
    path.write_text(path.read_text().replace(str(DATA / "ros_balancer.toml"),
                                             str(tmp_path / "ros_balancer.toml")))
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(load_derivation(path))
    said = " ".join(c.explanation for c in result.causes)
    named = "A[1,1]: the document has m_w where the moment of inertia Iyy(left_wheel) + " \
        "Iyy(right_wheel) about its own centre of mass × R**(-2) (2*J_w/R**2 in the " \
        "document's symbols) fits"                  # as the element's naming says it
    if uniform_urdf:
        assert named not in said and "uniform" in said, said
    else:
        assert result.equivalent is False and named in said, said
