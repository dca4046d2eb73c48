"""Documents written as a user writes them — symbols for masses, lengths and radii, not Khalil's
parameters — judged on parameter sets that draw the geometry too.

- the rolling disc of SymPy's mechanics documentation (Kane's method, inertias m r²/4 and
  m r²/2, the equations solved for the speed rates) agrees on ``rolling_coin`` when the file
  says the disc is uniform;
- a uniform ball's I = 2/5 m r² and its small oscillations at the bottom of a bowl,
  ω² = g/((R − r)(1 + 2/5)), agree on ``sphere_paraboloid``; with 2/3 each differs and the
  factor is named;
- l1² written for l1 in a two-link arm whose upper arm is 1 m long differs (on the URDF's own
  numbers it is invisible: checked against the truth directly); the same error in the shipped
  rod pendulum (its rod is 1 m long) is found;
- seed 000's 4.13 keeps "power: G where G**2 fits" and no longer offers the factor 2/7 that
  held only at the URDF's gear ratio.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from conftest import SEED
from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model
from wheeled_dyn.compare import ComparisonEngine
from wheeled_dyn.compare.sides.document import model_value
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.models.registry import model_parameters

DATA = Path(__file__).parent / "data"
KANE = DATA / "geometry" / "rolling_disc_kane.toml"
BOWL = DATA / "geometry" / "ball_in_bowl.toml"
ROD = DATA / "geometry" / "rod_pendulum_lengths.toml"
ARM = DATA / "two_link_arm" / "arm_lagrange.toml"
#: The comparison's grid here: structural errors show on a few hundred states.
SAMPLES, PARAM_SETS = 200, 3


def _compare(path: Path):
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))


def _variant(path: Path, tmp_path: Path, old: str, new: str, drop: str = "") -> Path:
    r"""A copy of ``path`` with ``old`` written ``new`` (and the line ``drop`` left out), beside
    the original's model file when it names one by path."""
    text = path.read_text()
    assert old in text and (not drop or drop in text)
    text = text.replace(old, new)
    if drop:
        text = text.replace(drop + "\n", "")
    out = tmp_path / path.name
    out.write_text(text.replace('model = "two_link_arm.toml"',
                                f'model = "{(path.parent / "two_link_arm.toml").as_posix()}"'))
    return out


def _by_element(result) -> dict:
    return {r.element: r for r in result.records}


def test_sympy_rolling_disc_kane_agrees_when_the_disc_is_uniform(tmp_path):
    result = _compare(KANE)
    assert result.records and all(r.verdict == "agrees" for r in result.records), \
        [(r.element, r.verdict, r.texts) for r in result.records if r.verdict != "agrees"]
    # without saying the disc is uniform, its inertias m r^2/4, m r^2/2 are not the coin's
    loose = _compare(_variant(KANE, tmp_path, "[assumes]", "", 'uniform = ["coin"]'))
    assert any(r.verdict != "agrees" for r in loose.records)


def test_uniform_ball_inertia_and_bowl_frequency_agree():
    records = _by_element(_compare(BOWL))
    assert {r.verdict for r in records.values()} == {"agrees"}, records
    assert any(r.step == "frequency" for r in records.values())


def test_two_thirds_for_two_fifths_differs_with_its_factor(tmp_path):
    result = _compare(_variant(BOWL, tmp_path, "2/5", "2/3"))
    claim = next(r for r in result.records if r.step == "claim")
    frequency = next(r for r in result.records if r.step == "frequency")
    assert claim.verdict == frequency.verdict == "differs"
    assert any(d.startswith("factor") and "5/3" in d for d in claim.texts), claim.texts
    # (3/5)/(5/7) = 21/25 = 0.84: the square of the frequency's factor
    assert any("0.84" in d for d in frequency.texts), frequency.texts
    assert any(d.startswith("factor") for d in frequency.texts), frequency.texts


def test_arm_agrees_and_l1_squared_for_l1_differs_on_a_one_metre_upper_arm(tmp_path):
    wm = load_model(str(DATA / "two_link_arm" / "two_link_arm.toml"))
    assert model_parameters(wm)["origin_x(elbow)"] == 1.0 == model_parameters(wm)["l1"]
    assert all(r.verdict == "agrees" for r in _compare(ARM).records)
    planted_path = _variant(ARM, tmp_path, "(m1/2 + m2)*g*l1*cos(q1)",
                            "(m1/2 + m2)*g*l1**2*cos(q1)")
    records = _by_element(_compare(planted_path))
    assert records["Q[1]"].verdict == "differs"
    assert any(d.startswith("power: l1**2 where l1 fits") for d in records["Q[1]"].texts)
    assert all(r.verdict == "agrees" for e, r in records.items() if e != "Q[1]")
    # on the URDF's own numbers the planted Q[1] is the truth's: only drawn lengths show it
    d = load_derivation(planted_path)
    values = model_parameters(wm)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm))
    sub = {s.symbol: model_value(s.value, values) for s in d.symbols.values()
           if s.value is not None}
    Q = sp.lambdify(list(d.positions), d.read_off().Q.xreplace(sub), "numpy")
    rng = np.random.default_rng(SEED)
    for _ in range(5):
        q = rng.uniform(-np.pi, np.pi, 2)
        assert np.allclose(np.ravel(Q(*q)), cmap.terms(q, np.zeros(2)).Q, rtol=1e-12,
                           atol=1e-12)


def test_rod_pendulum_length_error_is_found(tmp_path):
    assert model_parameters(load_model("rod_pendulum"))["length(rod)"] == 1.0
    assert all(r.verdict == "agrees" for r in _compare(ROD).records)
    records = _by_element(_compare(_variant(ROD, tmp_path, "m*g*l/2*sin(theta)",
                                            "m*g*l**2/2*sin(theta)")))
    assert records["Q[1]"].verdict == "differs"
    assert any(d.startswith("power: l**2 where l fits") for d in records["Q[1]"].texts)
    frequency = _compare(_variant(ROD, tmp_path, "sqrt(3*g/(2*l))", "sqrt(3*g/(2*l**2))"))
    assert next(r for r in frequency.records if r.step == "frequency").verdict == "differs"


@pytest.mark.parametrize("element", ["A[1,2]", "A[2,1]"])
def test_seed000_4_13_keeps_power_and_loses_the_stray_factor(element):
    path = next(p for p in builtin_derivations("seed000")
                if p.name == "p4_13_differential_theta1.toml")
    record = _by_element(_compare(path))[element]
    assert record.verdict == "differs"
    assert any(d.startswith("power: G where G**2 fits") for d in record.texts)
    assert not any(d.startswith("factor") for d in record.texts), record.texts


def test_the_family_search_names_the_link_that_must_be_uniform(tmp_path):
    r"""The arm's file without its [assumes]: the forearm's terms agree only if the forearm
    is a uniform body (the per-link family), the upper arm's gravity term needs every link."""
    result = _compare(_variant(ARM, tmp_path, "[assumes]", "",
                               'uniform = ["upper_arm", "forearm"]'))
    records = _by_element(result)
    for element in ("A[2,2]", "Q[2]", "h[2]:dq1*dq1"):
        assert records[element].verdict == "agrees_if"
        assert records[element].texts[0] == "agrees only if forearm is a uniform body " \
            "(mass and size scaled as a whole, its lengths with it)", records[element].texts
    assert records["Q[1]"].verdict == "agrees_if"
    assert "every link keeps the URDF's proportions" in records["Q[1]"].texts[0]


def test_an_unknown_joint_or_length_is_one_error_naming_the_file_and_line(tmp_path, capsys):
    from wheeled_dyn.cli.main import main
    for old, new, name in (('"origin_x(elbow)"', '"origin_x(elbw)"', "elbw"),
                           ('"length(forearm)"', '"tyre_radius(forearm)"', "tyre_radius(forearm)")):
        path = _variant(ARM, tmp_path, old, new)
        model = str(DATA / "two_link_arm" / "two_link_arm.toml")
        assert main(["compare", model, str(path), "--out", str(tmp_path / "out")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and path.name in err[0] and name in err[0], err
        assert f"{path.name}:" in err[0] and "symbols." in err[0], err
