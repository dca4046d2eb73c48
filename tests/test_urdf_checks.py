"""A bad URDF is one error naming the link or joint, before Pinocchio reads it.

Each bad file is the shipped WIP's URDF (urdf/wip.urdf) with one mutation, written to a
temporary folder: the model builder raises the project's error (``InputFileError`` for the
file and its tree, ``ModelError`` for inertial data, with the link as ``item``) naming the
link or joint, and the command line exits 2 with that one line on stderr. A URDF with a cycle
of joints used to end the process with a segmentation fault: it is also run as a separate
process. Inertia tensors are checked by their principal moments: tensors rotated by a seeded
random rotation are judged as their diagonal forms, within the checks' tolerance.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn.cli.main import main
from wheeled_dyn.errors import InputFileError, ModelError
from wheeled_dyn.models import ModelSpec, build_wheeled_model, read_urdf
from wheeled_dyn.models.urdf_checks import INERTIA_TOL
from wheeled_dyn.paths import urdf_dir

WIP_URDF = urdf_dir() / "wip.urdf"
#: Seconds the command may take on a bad URDF (a crash or a hang fails instead).
CLI_TIMEOUT = 120
#: Random rotations applied to each inertia tensor of the rotation test.
N_ROTATIONS = 3
#: Relative excess of I_c over I_a + I_b, in units of the checks' tolerance: beyond it
#: (rejected) and within it (accepted, rounding in a URDF's printed digits).
OUTSIDE_TOL, INSIDE_TOL = 100.0, 0.1

MODEL_FILE = """name = "{name}"
[urdf]
path = "{urdf}"
[base]
type = "planar"
body = "body"
up = [0.0, 1.0, 0.0]
pitch = true
[wheels]
links = ["wheel_left", "wheel_right"]
radius = 0.25
"""


def _replace_once(text: str, old: str, new: str) -> str:
    assert text.count(old) == 1, old
    return text.replace(old, new)


def _in_link(text: str, link: str, pattern: str, new: str) -> str:
    r"""``text`` with the first match of ``pattern`` inside ``<link name="link">`` replaced."""
    start = text.index(f'<link name="{link}">')
    end = text.index("</link>", start)
    block, n = re.subn(pattern, new, text[start:end], count=1, flags=re.S)
    assert n == 1, (link, pattern)
    return text[:start] + block + text[end:]


def _mass(text: str, link: str, value: str) -> str:
    return _in_link(text, link, r'<mass value="[^"]*"/>', f'<mass value="{value}"/>')


def _inertia(text: str, link: str, I: np.ndarray) -> str:
    r"""``text`` with the link's inertia tensor (about its centre of mass) set to ``I``."""
    entries = dict(ixx=I[0, 0], ixy=I[0, 1], ixz=I[0, 2], iyy=I[1, 1], iyz=I[1, 2], izz=I[2, 2])
    attrs = " ".join(f'{k}="{float(v)!r}"' for k, v in entries.items())
    return _in_link(text, link, r"<inertia [^>]*/>", f"<inertia {attrs}/>")


def _joint(name: str, parent: str, child: str) -> str:
    return (f'  <joint name="{name}" type="fixed">\n    <parent link="{parent}"/>\n'
            f'    <child link="{child}"/>\n  </joint>\n')


def _add(text: str, element: str) -> str:
    return _replace_once(text, "</robot>", element + "</robot>")


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / f"{name}.urdf"
    path.write_text(text)
    return path


def _spec(path: Path, **changes) -> ModelSpec:
    base = dict(name="test", urdf=path, body="body", wheels=("wheel_left", "wheel_right"),
                up=(0.0, 1.0, 0.0))
    return ModelSpec(**{**base, **changes})


def _line(path: Path, line: int) -> str:
    return path.read_text().splitlines()[line - 1]


def _rotation(rng: np.random.Generator) -> np.ndarray:
    r"""A random proper rotation (QR of a Gaussian matrix, signs fixed)."""
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


BASE = WIP_URDF.read_text()

#: name: (mutated URDF text, names the message must contain, joint on the reported line).
TREE_CASES = {
    "cycle": (_add(BASE, _joint("loop_joint", "wheel_right", "body")),
              ("body", "wheel_right", "wheel_right_joint", "loop_joint", "cycle"), "loop_joint"),
    "two_parents": (_add(BASE, _joint("second_joint", "wheel_left", "wheel_right")),
                    ("second_joint", "wheel_right", "wheel_right_joint", "already the child"),
                    "second_joint"),
    "missing_child": (_replace_once(BASE, '<child link="wheel_right"/>',
                                    '<child link="wheel_middle"/>'),
                      ("wheel_right_joint", "wheel_middle", "not defined"), "wheel_right_joint"),
    "missing_parent": (_replace_once(BASE, '<parent link="body"/>\n    <child link="wheel_left"/>',
                                     '<parent link="torso"/>\n    <child link="wheel_left"/>'),
                       ("wheel_left_joint", "torso", "not defined"), "wheel_left_joint"),
    "link_twice": (_add(BASE, '  <link name="wheel_left"/>\n'),
                   ("wheel_left", "defined twice"), None),
}

#: name: (mutated URDF text, link named (the error's item), other names the message contains).
INERTIAL_CASES = {
    "negative_mass": (_mass(BASE, "wheel_left", "-5.0"), "wheel_left", ("'-5.0'", "mass")),
    "zero_mass": (_mass(BASE, "wheel_left", "0"), "wheel_left", ("'0'", "mass")),
    "nan_mass": (_mass(BASE, "wheel_right", "nan"), "wheel_right", ("'nan'", "mass")),
    "text_mass": (_mass(BASE, "body", "heavy"), "body", ("'heavy'", "mass")),
    # Python's float() reads these, urdfdom does not: it dropped the whole <inertial>
    "underscore_mass": (_mass(BASE, "body", "6_0"), "body", ("'6_0'", "mass")),
    "full_width_mass": (_mass(BASE, "body", "６０"), "body", ("'６０'", "mass")),
    "underscore_inertia": (_in_link(BASE, "wheel_left", r'izz="[^"]*"', 'izz="0_2"'),
                           "wheel_left", ("izz", "'0_2'", "not a finite number")),
    "triangle": (_inertia(BASE, "body", np.diag([1.0, 1.0, 5.0])), "body",
                 ("triangle inequality", "accept_inertia")),
    "not_psd": (_inertia(BASE, "body", np.diag([6.25, -1.7, 5.45])), "body",
                ("not positive semi-definite", "-1.7")),
    "inf_inertia": (_in_link(BASE, "wheel_left", r'izz="[^"]*"', 'izz="inf"'), "wheel_left",
                    ("izz", "not a finite number")),
    "no_inertial": (_in_link(BASE, "wheel_left", r"<inertial>.*?</inertial>", ""), "wheel_left",
                    ("wheel_left_joint", "has no mass")),
    "massless_moving": (_inertia(_mass(BASE, "wheel_left", "0"), "wheel_left", np.diag([0.0] * 3)),
                        "wheel_left", ("wheel_left_joint", "has no mass",
                                       'lock = ["wheel_left_joint"]')),
}


def test_the_unmutated_copy_builds(tmp_path):
    wm = build_wheeled_model(_spec(_write(tmp_path, "wip", BASE)))
    assert [w.link for w in wm.wheels] == ["wheel_left", "wheel_right"]


@pytest.mark.parametrize("case", sorted(TREE_CASES))
def test_tree_errors_name_the_joint_and_its_line(tmp_path, case):
    text, names, joint = TREE_CASES[case]
    path = _write(tmp_path, case, text)
    with pytest.raises(InputFileError) as err:
        build_wheeled_model(_spec(path))
    message = str(err.value)
    assert err.value.path == path and message.startswith(str(path))
    assert all(name in message for name in names), message
    assert len(message.splitlines()) == 1
    if joint is not None:
        assert f'name="{joint}"' in _line(path, err.value.line)


def test_malformed_xml_names_line_and_column(tmp_path):
    path = _write(tmp_path, "malformed", _replace_once(BASE, '<mass value="60.0"/>',
                                                       '<mass value="60.0">'))
    with pytest.raises(InputFileError) as err:
        build_wheeled_model(_spec(path))
    assert err.value.path == path and "malformed XML" in str(err.value)
    assert err.value.line is not None and err.value.column is not None
    assert str(err.value).startswith(f"{path}:{err.value.line}:{err.value.column}: ")
    assert "</inertial>" in _line(path, err.value.line)     # where the parser found the mismatch


def test_missing_file(tmp_path):
    with pytest.raises(InputFileError) as err:
        build_wheeled_model(_spec(tmp_path / "absent.urdf"))
    assert err.value.path == tmp_path / "absent.urdf" and "no such URDF file" in str(err.value)


@pytest.mark.parametrize("case", sorted(INERTIAL_CASES))
def test_inertial_errors_name_the_link(tmp_path, case):
    text, link, names = INERTIAL_CASES[case]
    path = _write(tmp_path, case, text)
    with pytest.raises(ModelError) as err:
        build_wheeled_model(_spec(path))
    message = str(err.value)
    assert err.value.item == link and f"({link})" in message
    assert all(name in message for name in names), message
    assert f"{path.name}:" in message and len(message.splitlines()) == 1


def test_accept_inertia_lets_the_listed_link_through(tmp_path):
    path = _write(tmp_path, "triangle", INERTIAL_CASES["triangle"][0])
    assert build_wheeled_model(_spec(path, accept_inertia=("body",))).name == "test"
    with pytest.raises(ModelError):                      # the mass is still checked
        build_wheeled_model(_spec(_write(tmp_path, "neg", _mass(path.read_text(), "body", "-1")),
                                  accept_inertia=("body",)))


def test_massless_frames_and_thin_bodies_are_accepted(tmp_path):
    r"""A massless frame (mass 0, inertia 0) on a fixed joint, and a thin rod (one principal
    moment 0) that other bodies keep regular, are the limits the checks accept."""
    frame = ('  <link name="imu">\n    <inertial>\n      <mass value="0"/>\n'
             '      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>\n'
             '    </inertial>\n  </link>\n')
    text = _add(_add(BASE, frame), _joint("imu_joint", "body", "imu"))
    text = _inertia(text, "body", np.diag([6.25, 6.25, 0.0]))
    build_wheeled_model(_spec(_write(tmp_path, "frames", text)))


@pytest.mark.parametrize("moments,accepted", [
    ((1.0, 2.0, 3.0), True),                                   # a flat plate: I_a + I_b = I_c
    ((1.0, 2.0, 3.0 * (1 + INSIDE_TOL * INERTIA_TOL)), True),
    ((1.0, 2.0, 3.0 * (1 + OUTSIDE_TOL * INERTIA_TOL)), False),
    ((1.0, 1.0, 5.0), False),
    ((-OUTSIDE_TOL * INERTIA_TOL, 2.0, 2.0), False),          # slightly negative moment
    ((2.0, 3.0, 4.0), True),
])
def test_rotated_inertia_is_judged_by_its_principal_moments(tmp_path, moments, accepted):
    rng = np.random.default_rng(SEED)
    for k in range(N_ROTATIONS):
        Rm = _rotation(rng)
        I = Rm @ np.diag(moments) @ Rm.T
        assert not np.allclose(I, np.diag(np.diag(I)))       # products of inertia present
        path = _write(tmp_path, f"rotated{k}", _inertia(BASE, "body", (I + I.T) / 2))
        if accepted:
            read_urdf(path)
        else:
            with pytest.raises(ModelError) as err:
                read_urdf(path)
            assert err.value.item == "body"


def _model_file(tmp_path: Path, name: str, text: str) -> Path:
    _write(tmp_path, name, text)
    model = tmp_path / f"{name}.toml"
    model.write_text(MODEL_FILE.format(name=name, urdf=f"{name}.urdf"))
    return model


@pytest.mark.parametrize("case,names", [
    ("triangle", ("body", "triangle inequality")),
    ("missing_child", ("wheel_right_joint", "wheel_middle")),
    ("no_inertial", ("wheel_left", "wheel_left_joint")),
])
def test_cli_matrices_of_a_model_file_with_a_bad_urdf(tmp_path, capsys, case, names):
    text = {**TREE_CASES, **INERTIAL_CASES}[case][0]
    assert main(["matrices", str(_model_file(tmp_path, case, text))]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("wheeled-dyn: error: "), captured.err
    assert all(name in lines[0] for name in names) and captured.out == ""


def test_cli_model_starter_of_a_bad_urdf(tmp_path, capsys):
    urdf = _write(tmp_path, "two_parents", TREE_CASES["two_parents"][0])
    out = tmp_path / "two_parents.toml"
    assert main(["model", str(urdf), "--out", str(out)]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and "second_joint" in lines[0] and "wheel_right" in lines[0]
    assert not out.exists()


def test_cli_cycle_is_an_error_not_a_crash(tmp_path):
    r"""The cycle that used to crash the model builder (segmentation fault), as a process."""
    model = _model_file(tmp_path, "cycle", TREE_CASES["cycle"][0])
    proc = subprocess.run([sys.executable, "-m", "wheeled_dyn.cli.main", "matrices", str(model)],
                          capture_output=True, text=True, timeout=CLI_TIMEOUT)
    assert proc.returncode == 2, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "cycle" in lines[0] and "loop_joint" in lines[0], proc.stderr
    assert "Traceback" not in proc.stderr and proc.stdout == ""


def test_nan_is_not_a_mass(tmp_path):
    r"""A NaN mass (any spelling float() reads) compares false with everything: it is not
    taken for a positive mass."""
    path = _write(tmp_path, "nan", _mass(BASE, "body", "NaN"))
    with pytest.raises(ModelError) as err:
        read_urdf(path)
    assert err.value.item == "body"


@pytest.mark.parametrize("mutation, named", [
    (lambda t: t.replace("<robot ", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" ', 1)
     .replace("</robot>", '  <xacro:include filename="$(find wip)/wheel.xacro"/>\n</robot>'),
     "<xacro:include>"),
    (lambda t: re.sub(r'<mass value="[^"]*"/>', '<mass value="${body_mass}"/>', t, count=1),
     '"${body_mass}"')])
def test_a_xacro_source_is_named_so(tmp_path, mutation, named):
    r"""A xacro source given where a URDF goes (ROS users keep robot.urdf.xacro): its macros
    were left out and a robot of one link was built without a word (``${...}`` in a number
    was refused, without saying why). One error says it is xacro and how to expand it."""
    path = _write(tmp_path, "xacro", mutation(BASE))
    with pytest.raises(InputFileError) as err:
        read_urdf(path)
    message = str(err.value)
    assert "xacro source" in message and named in message and "expand it" in message, message
