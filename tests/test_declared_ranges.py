r"""A range the file declares for a position (``[coordinates] ranges``) is binding — the states
are drawn there only — and the report says so among the assumptions: a two-link arm (Spong,
Hutchinson & Vidyasagar's equations, :mod:`published_forms`) with :math:`q_2` written for
:math:`\sin q_2` in its velocity terms (a small angle's approximation not declared as a
linearisation) agrees when :math:`q_2` is declared to stay within ±1e-4 of zero, and differs
when it is not; the agreement was said with no word of the range."""

from __future__ import annotations

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3
RANGE = 'ranges = { q2 = [-0.0001, 0.0001] }'


def _small_angle(tmp_path, declared: bool):
    path = P.write(tmp_path, "arm", "equations", None)
    text = path.read_text()
    assert "sin(q2)" in text
    text = text.replace("sin(q2)", "q2")
    if declared:
        text = text.replace('units = { q1 = "rad", q2 = "rad" }',
                            'units = { q1 = "rad", q2 = "rad" }\n' + RANGE)
        assert RANGE in text
    path.write_text(text)
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(path))


def test_a_declared_range_is_said_where_it_decides(tmp_path):
    within = _small_angle(tmp_path, True)
    assert within.equivalent is True
    assert "q2 only in [-0.0001, 0.0001] (the file's ranges: compared there only)" in \
        within.assumes, within.assumes
    everywhere = _small_angle(tmp_path, False)
    assert everywhere.equivalent is False
    assert not any("ranges" in a for a in everywhere.assumes)


def test_a_narrow_range_is_said_among_the_causes(tmp_path):
    r"""A range this narrow decides: it is the first cause ("holds only if q2 stays in ..."),
    even where every element agrees; a wide one is not a cause."""
    from wheeled_dyn.compare.records import CauseKind
    within = _small_angle(tmp_path, True)
    first = within.causes[0]
    assert first.kind == CauseKind.ASSUMPTION
    assert "q2 stays in [-0.0001, 0.0001]" in first.explanation, first.explanation
    path = P.write(tmp_path, "arm", "equations", None)
    text = path.read_text().replace('units = { q1 = "rad", q2 = "rad" }',
                                    'units = { q1 = "rad", q2 = "rad" }\n'
                                    'ranges = { q2 = [-1.5, 1.5] }')
    path.write_text(text)
    wide = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    assert wide.equivalent is True and not wide.causes, wide.causes


def test_a_narrow_range_of_a_position_the_equations_lack_is_no_cause(tmp_path):
    r"""The cart-pole's cart position x (in no term of its equations) declared in [0, 0.03]:
    nothing is hidden, and nothing is said."""
    path = P.write(tmp_path, "pole", "equations", None)
    text = path.read_text()
    units = 'units = { x = "m", theta = "rad" }'
    assert units in text
    path.write_text(text.replace(units, units + "\nranges = { x = [0.0, 0.03] }"))
    result = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is True and not result.causes, result.causes
