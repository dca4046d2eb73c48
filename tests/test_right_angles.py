r"""Right angles as URDFs write them: π/2 rounded to 1.57 (8e-4 rad off) or 1.5708 (3.7e-6),
π to 3.14. A differential-drive robot written the TurtleBot way — wheel joints turned by
``rpy="-1.57 0 0"`` about a z axis, each wheel's inertia turned by ``rpy="1.5708 0 0"`` — is
the robot of ``data/published/dd_robot.urdf`` (exact angles) as its author meant it. Before,
its wheels spun about axes 8e-4 rad off the axle (every input element "0.9999997 × the truth")
and its wheel inertias had products of inertia of 3.7e-6 of their moments (on a probe's robot
so written, a correct derivation was "not right as a system", off by 1.7e-7): a planar
model's wheels are now turned onto
their axle, and an inertia's orientation within :data:`RIGHT_ANGLE_TOL` of a right angle is
read as one."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.models.conventions import RIGHT_ANGLE_TOL, right_angles
from wheeled_dyn.models.registry import load_model

DATA = Path(__file__).parent / "data" / "published"
EXACT = "-1.5707963267948966 0 0"
WHEEL = ('<origin xyz="0 0 0"/><mass value="0.5"/>\n      <inertia ixx="0.0009" ixy="0" '
         'ixz="0" iyy="0.0009" iyz="0" izz="0.0016"/>')
#: The same wheel tensor written about axes turned by a right angle about x (spin axis y).
TURNED = ('<origin xyz="0 0 0" rpy="1.5708 0 0"/><mass value="0.5"/>\n      <inertia '
          'ixx="0.0009" ixy="0" ixz="0" iyy="0.0016" iyz="0" izz="0.0009"/>')
#: Agreement of the rounded robot's inertias with the exact one's.
SAME_TOL = 1e-15


@pytest.mark.parametrize("angle, expected", [
    (1.5708, np.pi / 2), (-1.57, -np.pi / 2), (3.14, np.pi), (0.0015, 0.0), (0.005, 0.005),
    (1.56, 1.56)])
def test_right_angles_within_the_tolerance_only(angle, expected):
    assert right_angles(np.array([angle]))[0] == pytest.approx(expected, abs=0.0, rel=1e-15)
    assert RIGHT_ANGLE_TOL < 0.005


def _rounded(tmp_path: Path) -> Path:
    text = (DATA / "dd_robot.urdf").read_text()
    assert text.count(EXACT) == 2 and text.count(WHEEL) == 2
    text = text.replace(EXACT, "-1.57 0 0").replace(WHEEL, TURNED)
    (tmp_path / "dd_robot.urdf").write_text(text)
    (tmp_path / "dd_robot.toml").write_text((DATA / "dd_robot.toml").read_text())
    return tmp_path / "dd_robot.toml"


def test_the_rounded_robot_is_the_exact_one(tmp_path):
    rounded, exact = load_model(str(_rounded(tmp_path))), load_model(str(DATA / "dd_robot.toml"))
    data = rounded.model.createData()
    pin.forwardKinematics(rounded.model, data, pin.neutral(rounded.model))
    for w, e in zip(rounded.wheels, exact.wheels):
        axis = data.oMi[w.joint_id].rotation @ np.array([0.0, 0.0, 1.0])
        assert abs(abs(axis[1]) - 1.0) <= SAME_TOL, axis
        a = rounded.model.inertias[w.joint_id].toDynamicParameters()
        b = exact.model.inertias[e.joint_id].toDynamicParameters()
        assert np.abs(a - b).max() <= SAME_TOL, (a, b)


def test_a_correct_derivation_of_the_rounded_robot_is_right(tmp_path):
    model = _rounded(tmp_path)
    text = (DATA / "dd_swivel_vw.toml").read_text().replace('model = "dd_swivel.toml"',
                                                            f'model = "{model.name}"')
    (tmp_path / "doc.toml").write_text(text)
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(tmp_path / "doc.toml"))
    assert result.equivalent is True, [c.explanation for c in result.causes]
    # what the model read otherwise than the URDF writes is said, never silent
    notes = " ".join(result.model_readings)
    for link in ("left_wheel", "right_wheel"):
        assert f'link {link}: its inertial origin rpy="1.5708 0 0" is read as (π/2, 0, 0)' in notes, \
            result.model_readings
    assert notes.count("its axis is turned by 0.0008 rad onto the axle") == 2, result.model_readings
    assert not set(result.model_readings) & set(result.notes)
    from wheeled_dyn.report.html import derivation_html
    page = derivation_html(result)       # shown under the assumptions, not folded away
    assert page.index("The model reads its URDF so:") < page.index("Matrices: document")
    # the wheels' tensors turned by exact right angles: the truth's closed forms have no
    # remainder of rpyToMatrix's 6e-17 (A[1,2] printed -77715611723761*I_m/(2.25e29*R))
    for element in ("A[1,2]", "A[2,1]"):
        record = next(r for r in result.records if r.element == element)
        assert record.truth == "0", record.truth


#: MuJoCo reads the file's numbers as written: its mass matrix differs from the model's by the
#: rounding the model reads away (3.7e-6 rad of a wheel's tensor turned by 1.5708), no more.
ROUNDING_TOL = 1e-5


@pytest.mark.parametrize("rounded", [False, True])
def test_mujoco_reads_the_file_as_the_model_does_but_for_the_rounding(tmp_path, rounded):
    r"""An engine that does not read right angles (MuJoCo, from the URDF text) against the
    Pinocchio model the project builds from the same file (continuous joints made revolute,
    the inertias turned exactly): the mass matrices agree to round-off for the exact robot and
    to the rounding's order for the rounded one, at random joint angles."""
    mujoco = pytest.importorskip("mujoco", reason="MuJoCo is an optional test dependency "
                                                  "(pip install mujoco)")
    from wheeled_dyn.models.urdf_source import read_urdf
    path = (_rounded(tmp_path).with_suffix(".urdf") if rounded else DATA / "dd_robot.urdf")
    model = pin.buildModelFromXML(read_urdf(path).pinocchio_text())
    data = model.createData()
    m = mujoco.MjModel.from_xml_string(path.read_text())
    d = mujoco.MjData(m)
    index = [m.jnt_dofadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, model.names[j])]
             for j in range(1, model.njoints)]
    rng = np.random.default_rng(SEED)
    for _ in range(5):
        q = rng.uniform(-np.pi, np.pi, model.nq)
        d.qpos[index] = q
        mujoco.mj_forward(m, d)
        M = np.zeros((m.nv, m.nv))
        mujoco.mj_fullM(m, d, M)
        ours = pin.crba(model, data, q)
        ours = np.triu(ours) + np.triu(ours, 1).T
        off = np.abs(M[np.ix_(index, index)] - ours).max() / np.abs(ours).max()
        assert off <= (ROUNDING_TOL if rounded else 1e-12), off


#: The arm's elbow frame turned by a right angle about x (its axis then z, link 2's moments
#: about y and z exchanged): the same arm, as an arm's URDF with turned joint frames writes it.
TURNED_ELBOW = ('<origin xyz="0.8 0 0" rpy="{roll} 0 0"/>\n    <axis xyz="0 0 1"/>',
          'ixx="0.003" ixy="0" ixz="0" iyy="0.058" iyz="0" izz="0.06"')


def _turned_arm(folder: Path, roll: str) -> Path:
    r"""The two-link arm (``data/published``) with its elbow joint's origin turned by
    ``roll`` about x, and Spong's equations of it (:mod:`published_forms`), I2 its moment
    about the turned frame's z."""
    import published_forms as P
    folder.mkdir()
    urdf = (DATA / "two_link_arm.urdf").read_text()
    elbow = '<origin xyz="0.8 0 0" rpy="0 0 0"/>\n    <axis xyz="0 -1 0"/>'
    link2 = 'ixx="0.003" ixy="0" ixz="0" iyy="0.06" iyz="0" izz="0.058"'
    assert urdf.count(elbow) == 1 and urdf.count(link2) == 1
    (folder / "two_link_arm.urdf").write_text(
        urdf.replace(elbow, TURNED_ELBOW[0].format(roll=roll)).replace(link2, TURNED_ELBOW[1]))
    (folder / "two_link_arm.toml").write_text((DATA / "two_link_arm.toml").read_text())
    doc = P.write(folder, "arm", "equations", None)
    text = doc.read_text().replace(str(DATA / "two_link_arm.toml"),
                                   str(folder / "two_link_arm.toml"))
    doc.write_text(text.replace('I2 = { value = "IYY(link2)"', 'I2 = { value = "IZZ(link2)"'))
    return doc


@pytest.mark.parametrize("roll", ["1.5707963267948966", "1.5708"])
def test_a_joint_frame_turned_by_a_rounded_right_angle_is_turned_by_the_right_angle(tmp_path,
                                                                                     roll):
    r"""An arm's elbow frame turned by π/2 written 1.5708 (as SO-ARM101's URDF writes its
    joints): Spong's equations agree, as with the exact angle (they differed by 3.7e-6 of
    their rows: "the term … is 0.99999 × what fits"); the model's readings say the
    comparison turns it by the right angle, and its own matrices keep 1.5708."""
    doc = _turned_arm(tmp_path / roll.replace(".", "_"), roll)
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(load_derivation(doc))
    assert result.equivalent is True, result.equations
    said = any("origin rpy within" in x for x in result.model_readings)
    assert said is (roll == "1.5708"), result.model_readings
    wm = load_model(str(doc.parent / "two_link_arm.toml"))
    R = wm.model.jointPlacements[wm.model.getJointId("q2")].rotation
    assert abs(R[2, 1] - np.sin(float(roll))) <= 1e-15          # as written


def test_the_truth_in_the_documents_symbols_is_the_right_angles(tmp_path):
    r"""The arm's elbow frame turned by 1.5708: the truth shown in the document's symbols
    (and the corrected equations) is that of the right angle the comparison drew, not
    "0.99999936586377*I2 + 6.34e-7*XX_link2 …"."""
    doc = _turned_arm(tmp_path / "shown", "1.5708")
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(load_derivation(doc))
    a11 = next(r for r in result.records if r.element == "A[1,1]")
    assert a11.truth == "I1 + I2 + l1**2*m2 + 2*l1*lc2*m2*cos(q2) + lc1**2*m1 + lc2**2*m2", \
        a11.truth


def test_the_symbolic_command_takes_the_right_angles(tmp_path, capsys):
    r"""``wheeled-dyn symbolic`` of the arm whose elbow frame is turned by 1.5708: its closed
    forms are those of the right angle (as docs/model-format.md says), no
    "0.999999999993254*sin(…) + 3.67e-6*cos(…)"; with the exact angle written, the same."""
    from wheeled_dyn.cli.main import main
    outputs = []
    for roll in ("1.5708", "1.5707963267948966"):
        doc = _turned_arm(tmp_path / roll.replace(".", "_"), roll)
        assert main(["symbolic", str(doc.parent / "two_link_arm.toml")]) == 0
        outputs.append(capsys.readouterr().out)
    closed = [o[o.index("A(q) nu'"):] for o in outputs]
    assert "0.99999" not in closed[0] and "e-6" not in closed[0], closed[0]
    assert closed[0] == closed[1]


@pytest.mark.parametrize("rpy", ["1.5708 0 0.3", "0.3 -1.5708 0", "0.2 3.1416 -1.5708"])
def test_a_rounded_right_angle_beside_another_angle_is_the_right_angle(tmp_path, rpy):
    r"""An elbow frame turned by a rounded right angle and another angle (``rpy="1.5708 0
    0.3"``): the comparisons' parameter sets turn it by the exact right angle and the other
    angle as written — the frame of the same URDF written with π/2 to the last digit. It was
    kept as written, and a derivation of the robot its author meant differed by 10⁻⁶ of its
    elements (11 of 20, "no single-term diagnosis")."""
    from wheeled_dyn.models.conventions import right_angled_joints
    exact = " ".join(repr(float(right_angles(np.array([float(a)]))[0])) for a in rpy.split())
    elbow = '<origin xyz="0.8 0 0" rpy="0 0 0"/>'
    frames = []
    for name, angles in (("rounded", rpy), ("exact", exact)):
        folder = tmp_path / name
        folder.mkdir()
        urdf = (DATA / "two_link_arm.urdf").read_text()
        assert urdf.count(elbow) == 1
        (folder / "two_link_arm.urdf").write_text(
            urdf.replace(elbow, f'<origin xyz="0.8 0 0" rpy="{angles}"/>'))
        (folder / "two_link_arm.toml").write_text((DATA / "two_link_arm.toml").read_text())
        model = load_model(str(folder / "two_link_arm.toml")).model.copy()
        right_angled_joints(model)
        frames.append(np.asarray(model.jointPlacements[model.getJointId("q2")].rotation))
    assert np.abs(frames[0] - frames[1]).max() <= SAME_TOL, frames


@pytest.mark.parametrize("text, rounding", [
    ("1.5708", True), ("1.57", True), ("1.571", True), ("1.5707", True), ("3.14", True),
    ("3.1416", True), ("-1.5708", True), ("6.2832", True), ("1.5707963267948966", True),
    ("1.569", False), ("1.5700", False), ("3.1", True), ("0.001", False)])
def test_a_rounding_is_the_right_angle_to_its_digits(text, rounding):
    r"""An angle near a right angle is its rounding only where it is the right angle rounded
    or cut at the decimals it prints."""
    from wheeled_dyn.models.rounded_angles import is_rounding
    assert is_rounding(text) is rounding


def _arm_with_elbow(tmp_path, rpy: str):
    r"""The two-link arm as a user's model, its elbow joint's origin turned by ``rpy``, and
    the joints whose angles near right angles are no roundings, as they are meant."""
    from wheeled_dyn.models.rounded_angles import unrounded_joints
    folder = tmp_path / "arm"
    folder.mkdir()
    elbow = '<origin xyz="0.8 0 0" rpy="0 0 0"/>'
    urdf = (DATA / "two_link_arm.urdf").read_text()
    assert urdf.count(elbow) == 1
    (folder / "two_link_arm.urdf").write_text(
        urdf.replace(elbow, f'<origin xyz="0.8 0 0" rpy="{rpy}"/>'))
    (folder / "two_link_arm.toml").write_text((DATA / "two_link_arm.toml").read_text())
    wm = load_model(str(folder / "two_link_arm.toml"))
    return wm, unrounded_joints(wm.spec.urdf, RIGHT_ANGLE_TOL)


def test_an_angle_near_a_right_angle_that_is_no_rounding_is_kept(tmp_path):
    r"""An elbow frame turned by ``rpy="1.569 0 0.3"``: 1.569 is within the tolerance of
    π/2 but no rounding of it, so the frame is kept as written (a derivation of the URDF as
    written had differed, the frame turned by π/2), and the reading says so."""
    from wheeled_dyn.models.conventions import right_angled_joints
    wm, kept = _arm_with_elbow(tmp_path, "1.569 0 0.3")
    assert set(kept) == {"q2"} and kept["q2"] == (1.569, 0.0, 0.3), kept
    model = wm.model.copy()
    before = np.asarray(model.jointPlacements[model.getJointId("q2")].rotation).copy()
    assert right_angled_joints(model, kept=kept) == 0
    assert np.array_equal(np.asarray(model.jointPlacements[model.getJointId("q2")].rotation),
                          before)
    assert any("no rounding of it" in x for x in wm.readings), wm.readings


def test_a_rounded_right_angle_beside_an_angle_meant_as_written_is_made_exact(tmp_path):
    r"""An elbow frame turned by ``rpy="1.5708 0 1.569"``: 1.5708 is π/2 rounded, 1.569 is
    no rounding (an angle meant as written). The joint's turn is π/2 about x and 1.569 about
    z — the rounding made the right angle, the other angle kept (the whole frame was kept as
    written, 1.5708 with it, against the docs)."""
    import pinocchio as pin

    from wheeled_dyn.models.conventions import right_angled_joints
    wm, kept = _arm_with_elbow(tmp_path, "1.5708 0 1.569")
    assert kept == {"q2": (np.pi / 2, 0.0, 1.569)}, kept
    model = wm.model.copy()
    assert right_angled_joints(model, kept=kept) == 1
    turned = np.asarray(model.jointPlacements[model.getJointId("q2")].rotation)
    assert np.abs(turned - pin.rpy.rpyToMatrix(np.pi / 2, 0.0, 1.569)).max() <= 1e-15
