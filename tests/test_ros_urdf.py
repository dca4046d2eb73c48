"""A robot written the way ROS users write URDFs (REP 103), from ``wheeled-dyn model`` to
``matrices`` and ``compare`` with no hand edits (tests/data/ros_balancer).

The URDF has a massless base_footprint root, base_link (x forward, y left, z up), a torso fixed
on top (turned about z), wheel joints continuous about +y and -y, wheel cylinders turned by
rpy="1.5708 0 0" and "1.57 0 0", full inertia tensors with products of inertia. Its reduced
A, h = C nu, Q, B in the heading coordinates are checked against an independent derivation:
SymPy's KanesMethod of the same bodies with the rolling constraints (``ros_kane.py``), the body's
parameters composed from the URDF by hand here (not by Pinocchio). A derivation file in a
document's own symbols, mapped to the physical link parameters, agrees element by element; the
same with one wheel inertia term dropped differs there.
"""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from conftest import SEED
from ros_kane import kane_terms
from wheeled_dyn.cli.main import main
from wheeled_dyn.constraints import CoordinateMap
from wheeled_dyn.coordinates import builtin_coordinate_set
from wheeled_dyn.errors import ModelError
from wheeled_dyn.models.registry import load_model, model_parameters

DATA = Path(__file__).parent / "data" / "ros_balancer"
URDF = DATA / "ros_balancer.urdf"
MODEL = DATA / "ros_balancer.toml"
#: Agreement of the project's terms with Kane's, relative to each matrix's largest entry.
KANE_TOL = 1e-12
#: Random states compared with Kane's equations.
N_STATES = 8


def _rpy(r: float, p: float, y: float) -> np.ndarray:
    cr, sr, cp, sp_, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    Ry = np.array([[cp, 0, sp_], [0, 1, 0], [-sp_, 0, cp]])
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return Rz @ Ry @ Rx


def _numbers(text: str | None, n: int = 3) -> np.ndarray:
    return np.array([float(x) for x in text.split()]) if text else np.zeros(n)


def _urdf_bodies() -> dict[str, float]:
    r"""The Kane parameters from the URDF's numbers: base_link and the torso composed by hand
    (parallel-axis theorem, in base_link's axes), the left wheel's own inertia."""
    root = ET.parse(URDF).getroot()
    links = {link.get("name"): link for link in root.iter("link")}
    joints = {j.find("child").get("link"): j for j in root.iter("joint")}

    def inertial(name: str, R: np.ndarray, p: np.ndarray):
        node = links[name].find("inertial")
        o = node.find("origin")
        Ro = R @ _rpy(*_numbers(o.get("rpy")))
        c = p + R @ _numbers(o.get("xyz"))
        i = {k: float(v) for k, v in node.find("inertia").attrib.items()}
        J = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]],
                      [i["ixz"], i["iyz"], i["izz"]]])
        return float(node.find("mass").get("value")), c, Ro @ J @ Ro.T

    torso = joints["torso"].find("origin")
    parts = [inertial("base_link", np.eye(3), np.zeros(3)),
             inertial("torso", _rpy(*_numbers(torso.get("rpy"))), _numbers(torso.get("xyz")))]
    m = sum(p[0] for p in parts)
    c = sum(p[0] * p[1] for p in parts) / m
    J = sum(p[2] + p[0] * ((p[1] - c) @ (p[1] - c) * np.eye(3) - np.outer(p[1] - c, p[1] - c))
            for p in parts)
    mw, cw, Jw = inertial("left_wheel", np.eye(3), np.zeros(3))
    wheel = joints["left_wheel"].find("origin")
    cyl = links["left_wheel"].find("collision").find("geometry").find("cylinder")
    return {"m_b": m, "x_b": c[0], "y_b": c[1], "z_b": c[2], "I_xx": J[0, 0], "I_xy": J[0, 1],
            "I_xz": J[0, 2], "I_yy": J[1, 1], "I_yz": J[1, 2], "I_zz": J[2, 2], "m_w": mw,
            "J_w": Jw[1, 1], "K_w": Jw[0, 0], "R": float(cyl.get("radius")),
            "L": float(_numbers(wheel.get("xyz"))[1]), "g": 9.81}


@pytest.fixture(scope="module")
def kane():
    p, A, h, Q, B, _ = kane_terms()
    values = {p[k]: v for k, v in _urdf_bodies().items()}
    args = sp.symbols("psi theta dx dpsi dtheta", real=True)
    return [sp.lambdify(args, M.xreplace(values), "numpy") for M in (A, h, Q, B)]


def test_model_command_writes_the_shipped_file_then_matrices_and_compare_run(tmp_path, capsys):
    shutil.copy(URDF, tmp_path / URDF.name)
    out = tmp_path / MODEL.name
    assert main(["model", str(tmp_path / URDF.name), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "wheel pair found: left left_wheel" in printed and "body base_link" in printed
    assert "track 0.44 m" in printed and "forward = +x of base_link (REP 103)" in printed
    assert out.read_text() == MODEL.read_text()          # the shipped file has no hand edits
    from wheeled_dyn.models.conventions import convention_table
    for line in convention_table(load_model(str(out))).lines():
        assert line in printed
    assert "about the centre of mass, in base_link's axes" in printed
    assert main(["matrices", str(out), "--state", "phi=0.1,dx=0.5"]) == 0
    assert "conventions of model ros_balancer" in capsys.readouterr().out
    for name in ("ros_balancer_heading.toml", "ros_balancer_dropped_wheel.toml"):
        shutil.copy(DATA / name, tmp_path / name)
    assert main(["compare", str(out), str(tmp_path / "ros_balancer_heading.toml"),
                 str(tmp_path / "ros_balancer_dropped_wheel.toml"),
                 "--out", str(tmp_path / "reports")]) == 0
    lines = capsys.readouterr().out.splitlines()
    right = lines.index(next(x for x in lines if x.startswith("ros_balancer_heading.toml")))
    assert lines[right + 1].strip().startswith("45 agree") and "0 differ" in lines[right + 1]
    assert "0 differ in factorisation" in lines[right + 1]
    dropped = lines.index(next(x for x in lines if x.startswith("ros_balancer_dropped")))
    assert lines[dropped + 1].strip().startswith("44 agree") and "1 differ" in lines[dropped + 1]
    assert "A[1,1]" in lines[dropped + 2]


def test_reduced_terms_equal_an_independent_kane_derivation(kane):
    wm = load_model(str(MODEL))
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "heading"))
    T = np.diag([1.0, 1.0, -1.0])        # (dx, dpsi, dphi) = T (dx, dpsi, dtheta): phi = -theta
    P = np.diag([1.0, -1.0])             # model torques (about each joint axis) = P (u_l, u_r)
    A_k, h_k, Q_k, B_k = kane
    rng = np.random.default_rng(SEED)
    for _ in range(N_STATES):
        psi, theta = rng.uniform(-np.pi, np.pi, 2)
        dx, dpsi, dtheta = rng.normal(size=3)
        terms = cmap.terms(np.array([0.3, psi, -theta]), np.array([dx, dpsi, -dtheta]))
        expected = {"A": T @ A_k(psi, theta, dx, dpsi, dtheta) @ T,
                    "h": T @ np.ravel(h_k(psi, theta, dx, dpsi, dtheta)),
                    "Q": T @ np.ravel(Q_k(psi, theta, dx, dpsi, dtheta)),
                    "B": T @ B_k(psi, theta, dx, dpsi, dtheta) @ P}
        got = {"A": terms.A, "h": terms.C @ np.array([dx, dpsi, -dtheta]), "Q": terms.Q,
               "B": terms.B}
        assert np.allclose(got["h"], terms.h, rtol=0, atol=1e-12)
        for name, value in expected.items():
            scale = max(np.abs(value).max(), 1.0)
            assert np.abs(got[name] - value).max() <= KANE_TOL * scale, (name, got[name], value)


def test_physical_parameters_are_the_composed_body():
    values = model_parameters(load_model(str(MODEL)))
    body = _urdf_bodies()
    for name, key in (("M(base_link)", "m_b"), ("CX(base_link)", "x_b"), ("CZ(base_link)", "z_b"),
                      ("IXX(base_link)", "I_xx"), ("IXZ(base_link)", "I_xz"),
                      ("IYZ(base_link)", "I_yz"), ("IYY(left_wheel)", "J_w")):
        assert values[name] == pytest.approx(body[key], rel=1e-12, abs=1e-15), name
    m, c = values["M(base_link)"], body["y_b"]
    assert values["MY(base_link)"] == pytest.approx(m * c, rel=1e-12)
    assert values["XY(base_link)"] == pytest.approx(
        values["IXY(base_link)"] - m * body["x_b"] * body["y_b"], rel=1e-12)


def test_wheels_listed_against_the_geometry_are_refused(tmp_path):
    shutil.copy(URDF, tmp_path / URDF.name)
    swapped = MODEL.read_text().replace('links = ["left_wheel", "right_wheel"]',
                                        'links = ["right_wheel", "left_wheel"]')
    assert swapped != MODEL.read_text()
    (tmp_path / "swapped.toml").write_text(swapped)
    with pytest.raises(ModelError) as err:
        load_model(str(tmp_path / "swapped.toml"))
    assert "right_wheel" in str(err.value) and "left_wheel" in str(err.value)
    assert "against the geometry" in str(err.value)
    declared = swapped.replace('pitch = true', 'pitch = true\nforward = [-1.0, 0.0, 0.0]')
    (tmp_path / "backward.toml").write_text(declared)
    assert load_model(str(tmp_path / "backward.toml")).wheels[0].link == "right_wheel"


@pytest.mark.parametrize("link", ["base_footprint", "torso"])
def test_a_merged_link_parameter_is_refused_naming_its_body(tmp_path, capsys, link):
    text = (DATA / "ros_balancer_heading.toml").read_text()
    text = text.replace('model = "ros_balancer.toml"', f'model = "{MODEL}"')
    bad = text.replace('z_b  = { value = "CZ(base_link)"', f'z_b  = {{ value = "MZ({link})"')
    assert bad != text
    (tmp_path / "bad.toml").write_text(bad)
    assert main(["compare", str(MODEL), str(tmp_path / "bad.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert link in err and "base_link" in err and "symbols.z_b" in err


def test_no_wheel_pair_is_said_plainly(tmp_path, capsys):
    text = URDF.read_text().replace('rpy="1.5708 0 0"', 'rpy="0 0 0"')
    (tmp_path / "r.urdf").write_text(text)
    assert main(["model", str(tmp_path / "r.urdf"), "--out", str(tmp_path / "r.toml")]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith("no wheel pair found")
    assert "left_wheel_joint: left_wheel's collision cylinder axis is 1.57 rad from the joint " \
        in printed
    written = (tmp_path / "r.toml").read_text()
    assert "CHECK: a fixed base holds the root link in the air" in written


def test_symbolic_lists_both_kinds_of_parameters(capsys):
    assert main(["symbolic", str(MODEL), "--form", "intermediate"]) == 0
    out = capsys.readouterr().out
    assert "about base_link's origin, in its axes (Khalil)" in out
    assert "about the centre of mass, in base_link's axes" in out
    assert "torso: merged into base_link" in out
