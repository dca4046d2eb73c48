r"""Two symbols each written where the other fits, and one of a file's ``[definitions]``
written for another (:mod:`wheeled_dyn.compare.judge.swaps`).

- The cart with a double pendulum (``data/published/cart_double_pendulum*``, written for the
  tests by Lagrange's equations, as in Bogdanov, *Optimal control of a double inverted
  pendulum on a cart*, 2004): in the first link's equation the links' masses exchanged,
  :math:`I_1 + L_1^2 m_1 + a_1^2 m_2` for :math:`I_1 + L_1^2 m_2 + a_1^2 m_1` — no one symbol
  read as another everywhere fits, both read so do.
- The rotary pendulum (``data/published/furuta_products*``, ``furuta_principal``, after
  Cazzolato and Prime 2011, principal axes declared) with the pendulum's moments :math:`J_{yy}` and :math:`J_{zz}` exchanged in
  the arm's inertia.
- The cart's equations in the names of the solved file's ``[definitions]`` (its inertia
  entries :math:`M_{ij}`), :math:`M_{21}` written where :math:`M_{31}` fits in the third row.
The correct files agree (the control), and each planted error is named and nothing else
differs."""

from __future__ import annotations

import pytest

from conftest import SEED
from shipped_copies import published_copy
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation

#: The first link's inertia terms as the file prints them, and with its masses exchanged.
PRINTED = ("L1**2*ddth1*m2", "a1**2*ddth1*m1")
EXCHANGED = ("L1**2*ddth1*m1", "a1**2*ddth1*m2")
#: The equations in the inertia entries the solved file defines (its [definitions]).
IN_ENTRIES = [
    "M11*ddx + M12*ddth1 + M13*ddth2 = f1",
    "M21*ddx + M22*ddth1 + M23*ddth2 = f2",
    "{third}*ddx + M32*ddth1 + M33*ddth2 = f3",
]


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=500, param_sets=4, seed=SEED)


def _wrong(result) -> dict:
    return {r.element: r for r in result.records if r.verdict != Verdict.AGREES}


def test_two_masses_exchanged_in_an_element_are_named_together(engine, tmp_path):
    path = published_copy(tmp_path, "cart_double_pendulum", "cart_double_pendulum_equations",
                          *zip(PRINTED, EXCHANGED))
    result = engine.compare(load_derivation(path))
    wrong = _wrong(result)
    assert result.equivalent is False and list(wrong) == ["A[2,2]"], wrong
    assert any(x.kind == K.SWAP and x.text.endswith("m1 and m2 exchanged (each written where "
                                                    "the other fits)")
               for x in wrong["A[2,2]"].diagnoses), wrong["A[2,2]"].texts


def _entries_file(tmp_path, third: str):
    solved = published_copy(tmp_path, "cart_double_pendulum", "cart_double_pendulum_solved")
    text = solved.read_text()
    rows = ",\n".join(f'  "{r.format(third=third)}"' for r in IN_ENTRIES)
    path = tmp_path / "entries.toml"
    path.write_text(text[:text.index("[matrices]")] + f"[matrices]\nequations = [\n{rows}\n]\n")
    return path


@pytest.mark.parametrize("third, named", [("M31", None),
                                          ("M21", "M12 or M21 where M13 or M31 fits")])
def test_a_definition_written_for_another_is_named_by_its_names(engine, tmp_path, third,
                                                                named):
    result = engine.compare(load_derivation(_entries_file(tmp_path, third)))
    wrong = _wrong(result)
    if named is None:
        assert not wrong and result.equivalent is True, wrong
        return
    assert result.equivalent is False and list(wrong) == ["A[3,1]"], wrong
    assert any(x.kind == K.SWAP and x.text.endswith(named) for x in wrong["A[3,1]"].diagnoses), \
        wrong["A[3,1]"].texts


def test_two_moments_exchanged_in_a_rotary_pendulum_are_named_together(engine, tmp_path):
    path = published_copy(tmp_path, "furuta_products", "furuta_principal",
                          ("(Jyy + m2*l2**2)*sin(al)**2 + Jzz*cos(al)**2",
                           "(Jzz + m2*l2**2)*sin(al)**2 + Jyy*cos(al)**2"))
    result = engine.compare(load_derivation(path))
    wrong = _wrong(result)
    assert result.equivalent is False and list(wrong) == ["A[1,1]"], wrong
    assert any(x.kind == K.SWAP and "exchanged" in x.text and {x.written, x.fits} ==
               {"Jyy", "Jzz"} for x in wrong["A[1,1]"].diagnoses), wrong["A[1,1]"].texts
