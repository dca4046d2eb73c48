r"""Bad URDFs, model files and states are one clear error, never a traceback or a NaN result.

Each bad URDF is tests/data/ros_balancer's URDF with one attribute changed, written to a
temporary folder. ``wheeled-dyn model`` on it exits 2 with one line naming the file and the
link or joint, and writes no model file (it used to write the file, then fail with
Pinocchio's or yourdfpy's traceback, or accept the file without a word); the error is the
project's own and survives a pickle round trip. A model file naming a joint or link the URDF
does not have, a wheel that is fixed to the body, numbers too large for floating point (a
mass of 1e308, a radius of 1e300, a state of 1e308) are refused in the same way, naming the
file and the key; a product that overflows all the same is an error, not a NaN printed.
"""

from __future__ import annotations

import pickle
from pathlib import Path

import pytest

from wheeled_dyn.cli.main import main
from wheeled_dyn.errors import (InputFileError, LimitError, ModelError, StateError,
                                UnknownNameError, WheeledDynError)
from wheeled_dyn.models.registry import load_model
from wheeled_dyn.models.starter import inspect_urdf

DATA = Path(__file__).parent / "data" / "ros_balancer"
URDF_TEXT = (DATA / "ros_balancer.urdf").read_text()
MODEL_TEXT = (DATA / "ros_balancer.toml").read_text()
LEFT_INERTIA = 'ixx="0.0021" ixy="0" ixz="0" iyy="0.004" iyz="0" izz="0.0021"'
LEFT_REVOLUTE = ('type="revolute">\n    <limit lower="{lower}" upper="1" effort="1" '
                 'velocity="1"/>\n    <parent link="base_link"/>\n    <child link="left_wheel"/>')
LEFT_CONTINUOUS = 'type="continuous">\n    <parent link="base_link"/>\n    <child link="left_wheel"/>'

#: name: (text replaced (its first occurrence), replacement, error type, names in the message).
URDF_CASES = {
    "nan_origin": ('<origin xyz="0 0.22 0"', '<origin xyz="0 nan 0"', InputFileError,
                   ("left_wheel_joint", "origin", "finite")),
    "nan_axis": ('<axis xyz="0 1 0"/>', '<axis xyz="0 nan 0"/>', InputFileError,
                 ("left_wheel_joint", "axis", "finite")),
    "inf_rpy": ('rpy="0 0 0.4"', 'rpy="0 0 inf"', InputFileError, ("torso_joint", "rpy")),
    "limit_nan": (LEFT_CONTINUOUS, LEFT_REVOLUTE.format(lower="nan"), InputFileError,
                  ("left_wheel_joint", "lower", "finite")),
    "wheel_revolute": ('type="continuous"', 'type="revolute"', InputFileError,
                       ("left_wheel_joint", "revolute", "<limit")),
    "wheel_prismatic": ('type="continuous"', 'type="prismatic"', InputFileError,
                        ("left_wheel_joint", "prismatic", "<limit")),
    "unknown_type": ('type="continuous"', 'type="helical"', InputFileError,
                     ("left_wheel_joint", "helical", "continuous")),
    "short_axis": ('<axis xyz="0 1 0"/>', '<axis xyz="0 1"/>', InputFileError,
                   ("left_wheel_joint", "axis", "3 finite numbers")),
    "zero_axis": ('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>', InputFileError,
                  ("left_wheel_joint", "axis", "not all zero")),
    "nan_inertial_origin": ('xyz="0.02 -0.01 0.12"', 'xyz="nan -0.01 0.12"', InputFileError,
                            ("base_link", "<inertial><origin")),
    "inertia_missing": ('<inertia ixx="0.09"', '<nothing ixx="0.09"', ModelError,
                        ("base_link", "<inertial> without <inertia")),
    "inertia_neg": (LEFT_INERTIA, LEFT_INERTIA.replace('ixx="0.0021"', 'ixx="-0.0021"'),
                    ModelError, ("left_wheel", "positive semi-definite", "--accept-inertia")),
    "inertia_notpd": (LEFT_INERTIA, LEFT_INERTIA.replace('ixy="0"', 'ixy="0.01"'), ModelError,
                      ("left_wheel", "positive semi-definite", "--accept-inertia")),
    "inertia_triangle": (LEFT_INERTIA, LEFT_INERTIA.replace("0.0021", "0.001"), ModelError,
                         ("left_wheel", "triangle inequality", "--accept-inertia")),
    "mass_huge": ('<mass value="6.0"/>', '<mass value="1e308"/>', ModelError,
                  ("base_link", "'1e308'", "1e100")),
    # a second <mass> or <inertial>: the first was read without a word (which is meant?)
    "two_masses": ('<mass value="6.0"/>', '<mass value="6.0"/><mass value="8.5"/>', ModelError,
                   ("base_link", "2 <mass> elements")),
    "two_inertials": ("<inertial>", '<inertial><mass value="1"/><inertia ixx="1" ixy="0" '
                      'ixz="0" iyy="1" iyz="0" izz="1"/></inertial>\n    <inertial>',
                      ModelError, ("base_link", "2 <inertial> elements")),
}


def _urdf(tmp_path: Path, name: str, old: str = "", new: str = "") -> Path:
    r"""The ros_balancer URDF with the first ``old`` replaced by ``new``, as ``name.urdf``."""
    assert old in URDF_TEXT, old
    path = tmp_path / f"{name}.urdf"
    path.write_text(URDF_TEXT.replace(old, new, 1))
    return path


def _model(tmp_path: Path, old: str, new: str, urdf: Path | None = None) -> Path:
    r"""The ros_balancer model file (next to its URDF) with ``old`` replaced by ``new``."""
    assert old in MODEL_TEXT, old
    if urdf is None:
        urdf = _urdf(tmp_path, "ros_balancer")
    path = tmp_path / "robot.toml"
    path.write_text(MODEL_TEXT.replace(old, new, 1).replace("ros_balancer.urdf", urdf.name))
    return path


def _assert_pickles(err: WheeledDynError) -> None:
    back = pickle.loads(pickle.dumps(err))
    assert type(back) is type(err) and str(back) == str(err)


def _one_error_line(capsys: pytest.CaptureFixture[str]) -> str:
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("wheeled-dyn: error: "), captured.err
    assert "Traceback" not in captured.err
    return lines[0]


@pytest.mark.parametrize("case", sorted(URDF_CASES))
def test_bad_urdf_is_one_error_and_no_model_file(tmp_path, capsys, case):
    old, new, kind, names = URDF_CASES[case]
    urdf = _urdf(tmp_path, case, old, new)
    with pytest.raises(kind) as err:
        inspect_urdf(urdf)
    message = str(err.value)
    assert urdf.name in message and all(n in message for n in names), message
    assert len(message.splitlines()) == 1
    _assert_pickles(err.value)
    out = tmp_path / f"{case}.toml"
    assert main(["model", str(urdf), "--out", str(out)]) == 2
    line = _one_error_line(capsys)
    assert urdf.name in line and names[0] in line
    assert not out.exists() and list(tmp_path.iterdir()) == [urdf]


def test_a_bad_mass_names_the_line_of_its_mass(tmp_path):
    r"""A negative mass is named at the line of its ``<mass>``, not of its ``<link>`` (a
    newcomer's URDF writes the inertial over several lines)."""
    urdf = _urdf(tmp_path, "negative", '<mass value="6.0"/>', '<mass value="-6.0"/>')
    line = urdf.read_text().splitlines().index(
        next(x for x in urdf.read_text().splitlines() if '<mass value="-6.0"/>' in x)) + 1
    with pytest.raises(ModelError) as err:
        inspect_urdf(urdf)
    assert f"{urdf.name}:{line})" in str(err.value), (line, str(err.value))


@pytest.mark.parametrize("case", ["nan_origin", "wheel_revolute", "unknown_type", "short_axis",
                                  "nan_inertial_origin", "inertia_missing"])
def test_model_file_over_a_bad_urdf_is_one_error(tmp_path, case):
    r"""The same URDFs named by a model file: the model is refused before Pinocchio reads it
    (it printed urdfdom's 'Error:' lines and built a body without its mass, or raised
    Pinocchio's ValueError)."""
    old, new, kind, names = URDF_CASES[case]
    model = _model(tmp_path, "pitch = true", "pitch = true", _urdf(tmp_path, case, old, new))
    with pytest.raises(kind) as err:
        load_model(model)
    assert f"{case}.urdf" in str(err.value) and names[0] in str(err.value)
    _assert_pickles(err.value)


def test_accept_inertia_is_an_explicit_opt_in_of_the_model_command(tmp_path, capsys):
    old, new, _, _ = URDF_CASES["inertia_notpd"]
    urdf = _urdf(tmp_path, "notpd", old, new)
    out = tmp_path / "notpd.toml"
    assert main(["model", str(urdf), "--out", str(out), "--accept-inertia", "left_wheel"]) == 0
    assert 'accept_inertia = ["left_wheel"]' in out.read_text()
    assert load_model(out).name == "ros_balancer"
    capsys.readouterr()
    assert main(["model", str(urdf), "--out", str(tmp_path / "x.toml"), "--accept-inertia",
                 "ghost"]) == 2
    line = _one_error_line(capsys)
    assert "--accept-inertia" in line and "'ghost'" in line and "left_wheel" in line
    assert not (tmp_path / "x.toml").exists()


def test_accepted_inertia_with_a_negative_moment_is_still_one_error(tmp_path, capsys):
    r"""A negative diagonal entry: Pinocchio refuses it ('The 3d inertia should be positive',
    a traceback) even when accepted."""
    old, new, _, _ = URDF_CASES["inertia_neg"]
    urdf = _urdf(tmp_path, "neg", old, new)
    out = tmp_path / "neg.toml"
    assert main(["model", str(urdf), "--out", str(out), "--accept-inertia", "left_wheel"]) == 2
    line = _one_error_line(capsys)
    assert "neg.urdf" in line and "left_wheel" in line and "ixx" in line
    assert not out.exists()


@pytest.mark.parametrize("old,new,kind,names", [
    ('"left_wheel_joint" = "theta_l"', '"ghost_joint" = "theta_l"', UnknownNameError,
     ("[joints] aliases", "'ghost_joint'", "left_wheel_joint", "right_wheel_joint")),
    ("[joints.aliases]", '[checks]\naccept_inertia = ["ghost"]\n\n[joints.aliases]',
     UnknownNameError, ("[checks] accept_inertia", "'ghost'", "base_link", "left_wheel")),
    ('links = ["left_wheel", "right_wheel"]', 'links = ["torso", "right_wheel"]', ModelError,
     ("[wheels] links", "'torso'", "fixed to the body base_link", "torso_joint")),
    ("radius = 0.1 ", "radius = 1e300 ", InputFileError, ("wheels.radius", "1e100")),
    # a probe's: no file, line or key named, or the URDF named for the model file's typo
    ('type = "planar"', 'type = "hovering"', InputFileError, ("base.type", "'hovering'",
                                                              "planar, fixed, free")),
    ('links = ["left_wheel", "right_wheel"]', 'links = ["left_wheel", "left_wheel"]',
     InputFileError, ("wheels.links", "'left_wheel' is listed twice")),
    ('"right_wheel_joint" = "theta_r"', '"right_wheel_joint" = "theta_l"', InputFileError,
     ("joints.aliases", "'theta_l' names two joints")),
    ('body = "base_link"', 'body = "no_link"', UnknownNameError, ("[base] body", "'no_link'")),
    ('links = ["left_wheel", "right_wheel"]', 'links = ["left_wheel", "no_wheel"]',
     UnknownNameError, ("[wheels] links", "'no_wheel'")),
])
def test_model_file_naming_what_does_not_fit_is_one_error(tmp_path, capsys, old, new, kind,
                                                          names):
    model = _model(tmp_path, old, new)
    with pytest.raises(kind) as err:
        load_model(model)
    message = str(err.value)
    assert str(model) in message and all(n in message for n in names), message
    _assert_pickles(err.value)
    assert main(["matrices", str(model)]) == 2
    assert str(model) in _one_error_line(capsys)


def test_state_too_large_is_refused(capsys):
    import wheeled_dyn as wd
    with pytest.raises(StateError) as err:
        wd.matrices("wip", "seed001", phi=1e308, dx=1e308)
    assert "phi" in str(err.value) and "1e100" in str(err.value)
    _assert_pickles(err.value)
    assert main(["matrices", "wip", "--state", "phi=1e308,dx=1e308"]) == 2
    line = _one_error_line(capsys)
    assert "phi" in line and "1e100" in line and "nan" not in line


def test_overflowing_terms_are_an_error_not_nan(tmp_path, capsys):
    r"""Numbers within the bounds whose products overflow (a torso of 1e100 kg at 1e100 m,
    turning at 1e100 rad/s): the first element that is not finite is named."""
    import wheeled_dyn as wd
    urdf = _urdf(tmp_path, "heavy", '<mass value="3.5"/>', '<mass value="1e100"/>')
    urdf.write_text(urdf.read_text().replace('xyz="0.01 0 0.3"', 'xyz="0.01 0 1e100"'))
    model = _model(tmp_path, "pitch = true", "pitch = true", urdf)
    with pytest.raises(LimitError) as err:
        wd.matrices(str(model), dphi=1e100, dpsi=1e100)
    assert "model ros_balancer" in str(err.value) and "finite" in str(err.value)
    _assert_pickles(err.value)
    assert main(["matrices", str(model), "--state", "dphi=1e100,dpsi=1e100"]) == 2
    captured = capsys.readouterr()
    assert "nan" not in captured.out and "finite" in captured.err
    assert len(captured.err.strip().splitlines()) == 1, captured.err


def test_every_link_whose_inertia_fails_is_named_in_one_error(tmp_path, capsys):
    r"""Both wheels' inertias not positive semi-definite: one error names both and the one
    option that writes the file (a newcomer re-ran the command once per link)."""
    bad = LEFT_INERTIA.replace('ixy="0"', 'ixy="0.01"')
    path = tmp_path / "both.urdf"
    path.write_text(URDF_TEXT.replace(LEFT_INERTIA, bad))
    assert main(["model", str(path), "--out", str(tmp_path / "both.toml")]) == 2
    line = _one_error_line(capsys)
    assert "left_wheel" in line and "right_wheel" in line
    assert "--accept-inertia left_wheel,right_wheel" in line
    assert not (tmp_path / "both.toml").exists()
    out = tmp_path / "ok.toml"
    assert main(["model", str(path), "--out", str(out), "--accept-inertia",
                 "left_wheel,right_wheel"]) == 0
    assert load_model(out).name == "ros_balancer"


def test_a_starting_file_that_does_not_build_says_so(tmp_path, capsys):
    r"""A URDF with a <mimic> joint: the file is written (a start), and the last line says it
    does not build yet instead of sending the user to run matrices on it."""
    text = URDF_TEXT.replace('<joint name="right_wheel_joint" type="continuous">',
                             '<joint name="right_wheel_joint" type="continuous">\n'
                             '    <mimic joint="left_wheel_joint" multiplier="1" offset="0"/>',
                             1)
    path = tmp_path / "mimic.urdf"
    path.write_text(text)
    out = tmp_path / "mimic.toml"
    assert main(["model", str(path), "--out", str(out)]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert "does not build yet" in last and "check the lines marked CHECK" not in last


def test_a_joint_locked_outside_its_limits_is_one_error(tmp_path, capsys):
    r"""A newcomer locks an arm's joint at a value its URDF's limits exclude (a probe's
    SO-ARM101 shoulder_pan at 3.0 rad, limits ±1.92): one error naming the joint, the value
    and the limits (the matrices were printed, of a pose the robot cannot take)."""
    import shutil
    data = Path(__file__).parent / "data" / "published"
    shutil.copy(data / "two_link_arm.urdf", tmp_path / "two_link_arm.urdf")
    old = 'actuated = ["q1", "q2"]\ninputs = ["tau1", "tau2"]'
    text = (data / "two_link_arm.toml").read_text()
    assert old in text
    text = text.replace("{", "{{").replace("}", "}}").replace(
        old, 'locked = {{ q2 = {value} }}\nactuated = ["q1"]\ninputs = ["tau1"]')
    path = tmp_path / "arm.toml"
    path.write_text(text.format(value=20.0))
    assert main(["matrices", str(path)]) == 2
    line = _one_error_line(capsys)
    assert "q2" in line and "locked at 20" in line and "limits [-10, 10]" in line, line
    path.write_text(text.format(value=0.5))
    assert load_model(str(path)).model.nq == 1


def test_a_link_no_joint_moves_is_said_as_such(tmp_path):
    r"""A derivation naming the mass of a link that no joint moves (the two-link arm's base,
    fixed to the ground): one error saying the link does not move, listing the moving ones
    (it was "unknown link")."""
    import published_forms as P
    from wheeled_dyn.derivations import load_derivation
    from wheeled_dyn.derivations.errors import DerivationNameError
    from wheeled_dyn.cli.inputs import check_model_names
    doc = P.write(tmp_path, "arm", "equations", None)
    doc.write_text(doc.read_text().replace('m1 = { value = "M(link1)"', 'm1 = { value = "M(base)"'))
    with pytest.raises(DerivationNameError) as err:
        check_model_names(load_derivation(doc))
    text = str(err.value)
    assert "fixed to the ground" in text and "'base'" in text and "link1, link2" in text, text
    _assert_pickles(err.value)
