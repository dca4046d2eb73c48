r"""A special parameter family never explains, nor silently hides, a term the document writes.

The WIP's families (``no_products``, ``com_on_axis``, ``no_armature`` ...) set parameters to
zero. A document that writes :math:`MX_1\cos\varphi` in C does not take :math:`MX_1 = 0`:

- undeclared, a family that zeroes a symbol the document writes is no explanation: a term in
  :math:`MX_1` with the wrong sign was "agrees only if the centre of mass is on the axle"
  (element and equation), and a term in the armature 3/2 × what fits made its equation
  "agree only if the model's special parameter families hold", naming none;
- declared, it makes the document's own terms vanish in every parameter set: they are never
  compared, and a ``file_error`` cause says so first (the verdicts under the declaration
  stand: declarations bind);
- no shipped derivation declares a family that zeroes a symbol it writes;
- the parameters drawn are no family either: an equation times a factor of them that
  vanishes with the model's own numbers, or for a robot of other densities, is lost there.

The document is ``data/wip_true_seed001.toml`` (the WIP's true reduced equations, derived by
hand for general parameters, ``test_compare_planted.py``), with one planted error.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge.consistency import contradicted_families
from wheeled_dyn.compare.engine.judgement import document_functions
from wheeled_dyn.compare.grid.assumptions import declared
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import builtin_derivations, load_derivation

TRUE_FILE = Path(__file__).parent / "data" / "wip_true_seed001.toml"
SAMPLES, PARAM_SETS = 200, 3
C12 = "dpsi*(MY1*sin(phi) - MX1*cos(phi))"
A11 = "m_S + 2*m_C + 2*Iw3/R**2 + 2*I_a/R**2"


@pytest.fixture(scope="module")
def engine() -> ComparisonEngine:
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _file(tmp_path: Path, old: str, new: str, families: str = "") -> Path:
    text = TRUE_FILE.read_text()
    assert text.count(old) == 1, old
    text = text.replace(old, new)
    if families:
        text = text.replace("\n[matrices]", f"\n[assumes]\nfamilies = {families}\n\n[matrices]")
    path = tmp_path / "planted.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("old, new, element, kind, term", [
    (C12, C12.replace("- MX1", "+ MX1"), "C[1,2]", K.SIGN, "MX1*dpsi*cos(phi)"),
    (A11, A11.replace("2*I_a", "3*I_a"), "A[1,1]", K.FACTOR, "3*I_a/R**2")])
def test_a_family_that_zeroes_a_written_symbol_explains_nothing(engine, tmp_path, old, new,
                                                                 element, kind, term):
    result = engine.compare(load_derivation(_file(tmp_path, old, new)))
    record = next(r for r in result.records if r.element == element)
    assert record.verdict == Verdict.DIFFERS, record.texts
    assert any(d.kind == kind and d.term == term for d in record.diagnoses), record.texts
    assert not any(r.verdict == Verdict.AGREES_IF for r in result.records), \
        [(r.element, r.texts) for r in result.records if r.verdict == Verdict.AGREES_IF]
    row = int(element[2]) - 1
    assert result.equations[row].verdict == Verdict.DIFFERS, result.equations[row].diagnoses
    assert result.equivalent is False


@pytest.mark.parametrize("family, gone", [('["com_on_axis"]', "MX1, MZ1"),
                                          ('["no_armature"]', "I_a")])
def test_a_declared_family_that_zeroes_a_written_symbol_is_said_first(engine, tmp_path,
                                                                      family, gone):
    r"""The planted sign in C[1,2]'s MX1 term under a declared com_on_axis (and the true file
    under no_armature): the verdicts stand as declared, and the first cause says which
    written symbols the declaration makes vanish, unchecked."""
    path = _file(tmp_path, C12, C12.replace("- MX1", "+ MX1") if "com" in family else C12,
                 family)
    result = engine.compare(load_derivation(path))
    first = result.causes[0]
    assert first.kind == CauseKind.FILE_ERROR, result.causes
    assert f"under which {gone} " in first.explanation and "not compared" in \
        first.explanation, first.explanation


def test_no_shipped_derivation_declares_a_family_against_its_own_symbols():
    wrong = {}
    for group in ("seed001", "seed000", "seed002", "literature"):
        for path in builtin_derivations(group):
            d = load_derivation(path)
            if not d.n:
                continue
            found = contradicted_families(d, document_functions(d), declared(d), SEED)
            if found:
                wrong[path.name] = [(name, [str(s) for s in gone]) for name, gone in found]
    assert not wrong, wrong


A22 = "2*Iw2 + 2*m_C*L**2"


def test_a_declared_family_that_relates_two_written_symbols_is_said_first(engine, tmp_path):
    r"""A spurious term in the wheels' Iw3 − 2·Iw2 under a declared disc_wheels (a probe's
    4(J − 2K)): it vanishes in every set drawn, so the file agrees as declared, but the first
    cause says the family makes the two written symbols proportional and their difference
    uncompared (it was silent, where a family that zeroes a symbol said so). Undeclared,
    the term differs."""
    spurious = f"{A22} + 4*(Iw3 - 2*Iw2)"
    result = engine.compare(load_derivation(_file(tmp_path, A22, spurious, '["disc_wheels"]')))
    assert result.equivalent is True, result.equations
    first = result.causes[0]
    assert first.kind == CauseKind.FILE_ERROR and "not compared" in first.explanation, \
        result.causes
    assert "the file declares disc_wheels, under which Iw2 = Iw3/2" in first.explanation, \
        first.explanation
    plain = engine.compare(load_derivation(_file(tmp_path, A22, spurious)))
    assert plain.equivalent is not True


def test_no_shipped_derivation_declares_a_family_relating_its_own_symbols():
    from wheeled_dyn.compare.judge.consistency import related_families
    wrong = {}
    for group in ("seed001", "seed000", "seed002", "literature"):
        for path in builtin_derivations(group):
            d = load_derivation(path)
            if d.n:
                found = related_families(d, document_functions(d), declared(d), SEED)
                if found:
                    wrong[path.name] = [(name, [str(p) for p in pairs]) for name, pairs in found]
    assert not wrong, wrong


def test_declared_units_against_the_value_are_the_files_error(engine, tmp_path):
    r"""MX1 declared in kg·m² where its value MX(body) is kg·m (a first moment): the document
    is right as written (the comparison uses the value), so every verdict stands, and one
    ``file_error`` cause names the symbol, its declared units and its value's. The true file
    (MX1 in kg·m) has no such cause."""
    wrong = '{ value = "MX(body)", units = "kg*m**2" }'
    path = _file(tmp_path, '{ value = "MX(body)", units = "kg*m" }', wrong)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is True, result.equations
    said = [c.explanation for c in result.causes if c.kind == CauseKind.FILE_ERROR]
    assert said == ["the file declares MX1 in kg·m^2, but its value MX(body) is kg·m: the "
                    "declared units are wrong (the comparison uses the value; the units only "
                    "check the document's terms)"], result.causes
    right = engine.compare(load_derivation(TRUE_FILE))
    assert not [c for c in right.causes if c.kind == CauseKind.FILE_ERROR], right.causes


def test_a_plain_names_units_are_the_models_to_say(tmp_path):
    r"""A value that is a plain name (``R``; a gear ratio a model's ``[geometry]`` calls L) is
    the model's to say the units of, not the name's: R declared in kg is not judged (a
    probe's gear ratio named L, dimensionless, was "declared units wrong: L is m")."""
    from wheeled_dyn.compare.judge.units import contradicted_units
    path = _file(tmp_path, 'R   = { value = "R", units = "m"', 'R   = { value = "R", units = "kg"')
    assert contradicted_units(load_derivation(path)) == []


def test_no_shipped_derivation_declares_units_against_its_values():
    from wheeled_dyn.compare.judge.units import contradicted_units
    wrong = {path.name: contradicted_units(load_derivation(path))
             for group in ("seed001", "seed000", "seed002", "literature")
             for path in builtin_derivations(group)}
    assert not {k: v for k, v in wrong.items() if v}


STEPS = """title = "potential energy"
model = "wip"
[coordinates]
use = "seed001"
[symbols]
g = { value = "g", units = "m/s**2" }
MX1 = { value = "MX(body)", units = "kg*m" }
MY1 = { value = "MY(body)", units = "kg*m" }
d = { value = "d", units = "m" }
m_S = { value = "m_S", units = "kg" }
[[step]]
equation = "(U)"
kind = "potential energy"
value = "VALUE"
"""


@pytest.mark.parametrize("value, verdict", [
    ("g*(MX1*sin(phi) + MY1*cos(phi))", Verdict.AGREES),
    ("g*(-MX1*sin(phi) + MY1*cos(phi))", Verdict.DIFFERS),       # was "agrees only if" MX1 = 0
    ("g*m_S*d*cos(phi)", Verdict.AGREES_IF)])                      # d names no MX1: it may be
def test_a_step_is_held_to_the_symbols_it_writes(tmp_path, value, verdict):
    from wheeled_dyn.compare.steps.records import compare_steps
    path = tmp_path / "steps.toml"
    path.write_text(STEPS.replace("VALUE", value))
    (record,) = compare_steps(load_derivation(path), SEED)
    assert record.verdict == verdict, record.texts


@pytest.mark.parametrize("factor, equivalent", [("(m_S - 12*m_C)", False),     # 60 = 12 × 5
                                                ("(m_S - 11*m_C)**2", False),
                                                ("(m_S + 11*m_C)**2", True)])
def test_an_equation_lost_for_the_robot_of_the_file_is_not_equivalent(engine, tmp_path,
                                                                       factor, equivalent):
    r"""The WIP's second equation times a factor of its parameters: the parameter sets are
    drawn, where it never vanishes, but with the model's own numbers (m_S = 60 kg,
    m_C = 5 kg) :math:`m_S - 12 m_C = 0`: the equation is lost for the very robot of the file
    (it agreed). One that vanishes for other robots only, a body eleven times as heavy as a
    wheel (:math:`m_S = 11 m_C`), is found among robots of other densities (the record's
    masses and inertias scaled body by body); one that cannot vanish leaves it right."""
    import tomllib

    from test_compare_planted import _dumps
    from wheeled_dyn.models.wip_parameters import WipParameters
    p = WipParameters()
    assert (p.m_S, p.m_C) == (60.0, 5.0)
    data = tomllib.loads(TRUE_FILE.read_text())
    for key in ("A", "C", "B", "Q"):
        M = data["matrices"][key]
        if isinstance(M[1], list):
            M[1] = [f"{factor}*({e})" for e in M[1]]
        else:
            M[1] = f"{factor}*({M[1]})"
    path = tmp_path / "scaled.toml"
    path.write_text(_dumps(data))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is equivalent, [c.explanation for c in result.causes]
    if not equivalent:
        assert any(d.kind == K.SINGULAR for d in result.equations[1].diagnoses)


def test_a_tiny_body_kept_by_the_family_does_not_vanish(tmp_path):
    r"""A proof mass of 1 µg at 0.1 mm on a 1 kg cart (the cart-pole of
    ``tests/data/published`` with its pole made tiny): under ``urdf_structure`` its own moment
    J (3e-18 kg m², as in its URDF) is kept, not made 0 — the sets drawn without the family
    draw inertias of no particular size, grams, beside which J is 1e-15. A right file that
    declares the family and writes J had the cause "the file declares urdf_structure, under
    which J is 0"."""
    import shutil
    from pathlib import Path
    from wheeled_dyn.compare.engine import ComparisonEngine
    from wheeled_dyn.compare.records import CauseKind
    from wheeled_dyn.derivations import load_derivation
    data = Path(__file__).parent / "data" / "published"
    shutil.copy(data / "cart_pole.toml", tmp_path / "cart_pole.toml")
    urdf = (data / "cart_pole.urdf").read_text()
    for old, new in (('<origin xyz="0 0 0.5" rpy="0 0 0"/>\n      <mass value="0.3"/>',
                      '<origin xyz="0 0 0.0001" rpy="0 0 0"/>\n      <mass value="1e-09"/>'),
                     ('ixx="0.025" ixy="0" ixz="0" iyy="0.025" iyz="0" izz="0.0"',
                      'ixx="3e-18" ixy="0" ixz="0" iyy="3e-18" iyz="0" izz="0.0"')):
        assert old in urdf
        urdf = urdf.replace(old, new)
    (tmp_path / "cart_pole.urdf").write_text(urdf)
    import published_forms as P
    doc = tmp_path / "proof_mass.toml"
    text = P.POLE_HEAD.format(form="a proof mass", error="", model=tmp_path / "cart_pole.toml",
                              eqs=",\n".join(f'  "{e}"' for e in EQUATIONS))
    text = text.replace('families = ["urdf_proportions"]', 'families = ["urdf_structure"]')
    text = text.replace('l = { value = "CZ(pole)", units = "m" }\n',
                        'l = { value = "CZ(pole)", units = "m" }\n'
                        'J = { value = "IYY(pole)", units = "kg*m**2" }\n')
    assert "urdf_structure" in text and "IYY(pole)" in text
    doc.write_text(text)
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(load_derivation(doc))
    assert result.equivalent is True, result.equations
    assert not any(c.kind == CauseKind.FILE_ERROR for c in result.causes), result.causes


#: The cart with a pendulum of its own moment J about its centre of mass (Lagrange).
EQUATIONS = ("(M + m)*ddx + m*l*cos(theta)*ddtheta - m*l*sin(theta)*dtheta**2 - F = 0",
             "m*l*cos(theta)*ddx + (J + m*l**2)*ddtheta - m*g*l*sin(theta) = 0")
