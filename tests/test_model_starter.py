"""``wheeled-dyn model URDF``: the starting model file a user gets for their own robot.

The file written for the shipped WIP's URDF, read back as a model, gives the same A, C, Q, B
as the hand-written model file of the package (an identity between the generator and the
file it replaces), at random states; a URDF without a wheel pair gets a fixed base that
loads; bad places are one error line and nothing is overwritten.
"""

from __future__ import annotations

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn.cli.main import main
from wheeled_dyn.constraints import CoordinateMap
from wheeled_dyn.coordinates import builtin_coordinate_set
from wheeled_dyn.models.registry import load_model
from wheeled_dyn.paths import urdf_dir

#: Relative agreement of the generated model's terms with the shipped model's.
TERMS_TOL = 1e-10
#: Random states compared.
N_STATES = 6


def _terms(model, state):
    wm = load_model(model)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "heading"))
    return cmap.terms(*cmap.state_from(state))


def test_starter_of_the_wip_urdf_equals_the_shipped_model(tmp_path, capsys):
    out = tmp_path / "robot.toml"
    assert main(["model", str(urdf_dir() / "wip.urdf"), "--out", str(out)]) == 0
    assert "CHECK" in out.read_text()
    rng = np.random.default_rng(SEED)
    for _ in range(N_STATES):
        phi, dx, dpsi, dphi = rng.uniform(-1.0, 1.0, 4)
        state = {"phi": phi, "dx": dx, "dpsi": dpsi, "dphi": dphi}
        mine, shipped = _terms(str(out), state), _terms("wip", state)
        for name in ("A", "C", "Q", "B"):
            a, b = getattr(mine, name), getattr(shipped, name)
            scale = max(np.abs(b).max(), 1.0)
            assert np.abs(a - b).max() <= TERMS_TOL * scale, name


def test_starter_without_a_wheel_pair_is_a_fixed_base_that_loads(tmp_path):
    out = tmp_path / "disk.toml"
    assert main(["model", str(urdf_dir() / "rod_pendulum.urdf"), "--out", str(out)]) == 0
    text = out.read_text()
    assert 'type = "fixed"' in text
    assert load_model(str(out)).model.nv >= 1


def test_starter_names_a_swivel_caster_and_its_lock_loads(tmp_path):
    r"""A ROS robot's swivel caster (two continuous joints that are not wheels) is named with
    a CHECK line, and the lock it suggests, uncommented, makes the caster part of the body."""
    from pathlib import Path
    urdf = Path(__file__).parent / "data" / "published" / "dd_swivel.urdf"
    out = tmp_path / "robot.toml"
    assert main(["model", str(urdf), "--out", str(out)]) == 0
    text = out.read_text()
    assert "# CHECK: caster_swivel_joint, caster_wheel_joint move freely" in text
    assert "caster_swivel_joint" in load_model(str(out)).coordinate_names
    out.write_text(text.replace("# lock = [", "lock = ["))
    names = load_model(str(out)).coordinate_names
    assert "caster_swivel_joint" not in names and "caster_wheel_joint" not in names


def test_starter_pairs_the_wheels_on_one_axle_of_a_skid_steer(tmp_path):
    r"""Four wheels of one radius (a skid-steer: the robot of ``dd_robot.urdf`` with rear
    wheels added 0.3 m behind): the drive wheels are two on one axle, where the pair farthest
    apart (a diagonal one, whose wheels spin about parallel axes off the line between them)
    was taken and the model it wrote did not load; the model loads."""
    from pathlib import Path
    text = (Path(__file__).parent / "data" / "published" / "dd_robot.urdf").read_text()
    start = text.index('  <joint name="left_wheel_joint"')
    end = text.index('  <joint name="caster_joint"') if '  <joint name="caster_joint"' in text \
        else text.index("</link>", text.index('<link name="right_wheel">')) + len("</link>\n")
    rear = text[start:end].replace("left_wheel", "rear_left_wheel").replace(
        "right_wheel", "rear_right_wheel").replace('xyz="0 0.18 0"', 'xyz="-0.3 0.18 0"').replace(
        'xyz="0 -0.18 0"', 'xyz="-0.3 -0.18 0"')
    urdf = tmp_path / "skid.urdf"
    urdf.write_text(text[:end] + rear + text[end:])
    out = tmp_path / "robot.toml"
    assert main(["model", str(urdf), "--out", str(out)]) == 0
    wm = load_model(str(out))
    assert {w.link for w in wm.wheels} in ({"left_wheel", "right_wheel"},
                                           {"rear_left_wheel", "rear_right_wheel"})


@pytest.mark.parametrize("urdf", ["dd_robot.urdf", "dd_swivel.urdf"])
def test_starter_keeps_a_robot_on_casters_level(tmp_path, urdf):
    r"""A differential-drive robot on a caster ball (a sphere fixed under its chassis) or on a
    swivel caster: ``pitch = false``, the casters named (``true`` was written, a pendulum); the
    wheeled inverted pendulum of the WIP URDF stays ``true`` (the test above)."""
    from pathlib import Path
    out = tmp_path / "robot.toml"
    assert main(["model", str(Path(__file__).parent / "data" / "published" / urdf), "--out",
                 str(out)]) == 0
    text = out.read_text()
    fixed = [x for x in text.splitlines() if x.startswith("#") and " fixed " in x]
    assert fixed and not any(x.rstrip().endswith("1 0 0") for x in fixed), fixed  # no axis
    line = next(x for x in text.splitlines() if x.startswith("pitch"))
    assert line.startswith("pitch = false") and "caster" in line, line
    assert not load_model(str(out)).spec.pitch


def test_a_wheel_whose_collision_cylinder_is_turned_wrong_is_read_from_its_visual(tmp_path):
    r"""The robot of ``dd_robot.urdf`` with each wheel's collision cylinder turned off its axis
    (its visual one right, as happens in a URDF's collision blocks): the wheels are found,
    their radius read from the visual cylinder and said so, where it was "no wheel pair"."""
    from pathlib import Path
    text = (Path(__file__).parent / "data" / "published" / "dd_robot.urdf").read_text()
    old = '<collision><geometry><cylinder radius="0.08"'
    assert text.count(old) == 2
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(text.replace(old, '<collision><origin rpy="1.5708 0 0"/><geometry>'
                                      '<cylinder radius="0.08"'))
    out = tmp_path / "robot.toml"
    assert main(["model", str(urdf), "--out", str(out)]) == 0
    assert "read from left_wheel's visual cylinder" in out.read_text()
    assert {w.link for w in load_model(str(out)).wheels} == {"left_wheel", "right_wheel"}


def test_existing_file_is_kept_without_force(tmp_path, capsys):
    out = tmp_path / "robot.toml"
    out.write_text("mine")
    assert main(["model", str(urdf_dir() / "wip.urdf"), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and str(out) in err and "--force" in err
    assert out.read_text() == "mine"
    assert main(["model", str(urdf_dir() / "wip.urdf"), "--out", str(out), "--force"]) == 0
    assert out.read_text() != "mine"


@pytest.mark.parametrize("content,expected", [
    (None, "no such URDF file"),
    ("<robot name='r'><link name='a'/>", "a"),
])
def test_bad_urdf_is_one_error(tmp_path, capsys, content, expected):
    urdf = tmp_path / "r.urdf"
    if content is not None:
        urdf.write_text(content)
    assert main(["model", str(urdf), "--out", str(tmp_path / "r.toml")]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and str(urdf) in err and expected in err
    assert not (tmp_path / "r.toml").exists()


def test_an_arm_on_a_balancing_robot_is_no_caster(tmp_path):
    r"""The ROS balancer (``data/ros_balancer``) with a two-joint arm on top of its body
    (written for the test): the arm's links were read as casters, and the starter wrote
    ``pitch = false`` — a balancing robot carrying an arm kept level. A link above the drive
    wheels' tops is no caster: ``pitch = true``, the arm's joints still named as moving."""
    from pathlib import Path
    text = (Path(__file__).parent / "data" / "ros_balancer" / "ros_balancer.urdf").read_text()
    arm = "".join(f'''  <joint name="{name}_joint" type="revolute">
    <parent link="{parent}"/><child link="{name}"/><origin xyz="0 0 {z}"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="10" velocity="2"/>
  </joint>
  <link name="{name}">
    <inertial><origin xyz="0 0 0.1"/><mass value="0.5"/>
      <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.0002"/></inertial>
    <visual><geometry><cylinder radius="0.02" length="0.2"/></geometry></visual>
  </link>
''' for name, parent, z in (("upper_arm", "base_link", 0.4), ("forearm", "upper_arm", 0.2)))
    urdf = tmp_path / "armed.urdf"
    urdf.write_text(text.replace("</robot>", arm + "</robot>"))
    out = tmp_path / "robot.toml"
    assert main(["model", str(urdf), "--out", str(out)]) == 0
    text = out.read_text()
    line = next(x for x in text.splitlines() if x.startswith("pitch"))
    assert line.startswith("pitch = true"), line
    assert "upper_arm_joint, forearm_joint move freely" in text


def test_a_urdf_in_millimetres_gets_a_check_note(tmp_path):
    r"""The robot of ``dd_robot.urdf`` with its lengths written in millimetres (a CAD export):
    the starter says to check the units, beside the radius and track it read (a radius of
    80 m passed without a word); the robot in metres gets no such note."""
    import re
    from pathlib import Path

    from wheeled_dyn.models.starter import inspect_urdf
    source = Path(__file__).parent / "data" / "published" / "dd_robot.urdf"
    text = source.read_text()

    def mm(match: re.Match) -> str:
        values = " ".join(f"{1000 * float(v):g}" for v in match.group(2).split())
        return f'{match.group(1)}="{values}"'
    urdf = tmp_path / "robot_mm.urdf"
    urdf.write_text(re.sub(r'\b(xyz|radius|length|size)="([^"]*)"', mm, text))
    notes = inspect_urdf(urdf).notes
    assert any(n.startswith("CHECK units: a wheel radius of 80 m and a track of 360 m")
               for n in notes), notes
    assert not any("units" in n for n in inspect_urdf(source).notes)
    out = tmp_path / "robot.toml"
    assert main(["model", str(urdf), "--out", str(out)]) == 0
    assert "# CHECK units" in out.read_text()


def test_a_link_in_millimetres_beside_wheels_in_metres_is_noted(tmp_path):
    r"""Only the torso's centre of mass written in millimetres (0.15 → 150 m up): the wheels
    are plausible, and the starter said nothing; now the farthest centre of mass is named."""
    from pathlib import Path

    from wheeled_dyn.models.starter import inspect_urdf
    source = Path(__file__).parent / "data" / "ros_balancer" / "ros_balancer.urdf"
    text = source.read_text()
    origin = '<origin xyz="-0.015 0.01 0.15" rpy="0 0 0"/>'
    assert origin in text
    urdf = tmp_path / "torso_mm.urdf"
    urdf.write_text(text.replace(origin, '<origin xyz="-15 10 150" rpy="0 0 0"/>', 1))
    notes = inspect_urdf(urdf).notes
    assert any(n.startswith("CHECK units: link") and "centre of mass" in n for n in notes), \
        notes
    assert not any("units" in n for n in inspect_urdf(source).notes)


@pytest.mark.parametrize("old, new, expected", [
    # the left wheel 5 cm ahead: parallel spin axes, centres offset (it said "wheel spin axis
    # is not along the axle")
    ('<origin xyz="0 0.18 0"', '<origin xyz="0.05 0.18 0"', "the wheels are not on one axle: "
     "their spin axes are parallel, but the line between their centres is 0.138 rad off them "
     "(the centres 0.05 m apart"),
    # the left wheel turned a fifth of a radian about the vertical
    ('<origin xyz="0 0.18 0" rpy="-1.5707963267948966 0 0"',
     '<origin xyz="0 0.18 0" rpy="-1.5707963267948966 0 0.2"',
     "wheel spin axis is not along the axle (the line between the wheel centres): 0.2 rad off"),
])
def test_wheels_off_one_axle_are_named_as_they_are(tmp_path, old, new, expected):
    r"""Drive wheels a planar model cannot roll: the error says whether they are offset (one
    ahead of the other) or turned."""
    from pathlib import Path

    from wheeled_dyn.errors import ModelError
    text = (Path(__file__).parent / "data" / "published" / "dd_robot.urdf").read_text()
    assert text.count(old) == 1
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(text.replace(old, new))
    out = tmp_path / "robot.toml"
    assert main(["model", str(urdf), "--out", str(out)]) == 0
    with pytest.raises(ModelError) as caught:
        load_model(str(out))
    assert expected in str(caught.value), str(caught.value)


@pytest.mark.parametrize("kind", ["floating", "planar"])
def test_a_joint_of_several_coordinates_is_named_by_its_urdf_type(tmp_path, capsys, kind):
    r"""A caster on a ``floating`` or ``planar`` joint (a probe's ROS robot): the starter's
    reason named Pinocchio's joint class only (JointModelFreeFlyer), not what the URDF says."""
    from pathlib import Path
    text = (Path(__file__).parent / "data" / "ros_balancer" / "ros_balancer.urdf").read_text()
    caster = f'''  <joint name="caster_joint" type="{kind}">
    <parent link="base_link"/><child link="caster"/><origin xyz="0.1 0 -0.05"/>
  </joint>
  <link name="caster">
    <inertial><mass value="0.05"/>
      <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>
  </link>
'''
    urdf = tmp_path / "caster.urdf"
    urdf.write_text(text.replace("</robot>", caster + "</robot>"))
    main(["model", str(urdf), "--out", str(tmp_path / "robot.toml")])
    said = capsys.readouterr()
    assert f"URDF joint type '{kind}'" in said.out + said.err
    assert "caster_joint" in said.out + said.err


@pytest.mark.parametrize("radius", ["0", "-0.1"])
def test_a_wheel_radius_left_at_zero_names_the_file_and_line(tmp_path, radius):
    r"""A starter whose wheel radius reads 0 (no collision cylinder to read it from) loaded
    as written: one error naming the model file, the line and ``wheels.radius`` (it named
    only the model and the link, at build time)."""
    from wheeled_dyn.errors import WheeledDynError
    out = tmp_path / "robot.toml"
    assert main(["model", str(urdf_dir() / "wip.urdf"), "--out", str(out)]) == 0
    text = out.read_text()
    line = next(x for x in text.splitlines() if x.startswith("radius ="))
    out.write_text(text.replace(line, f"radius = {radius}"))
    at = text.splitlines().index(line) + 1
    with pytest.raises(WheeledDynError) as err:
        load_model(str(out))
    said = str(err.value)
    assert f"{out}:{at}: wheels.radius" in said and "positive" in said, said


@pytest.mark.parametrize("rpy, size", [("0 0 0", "0.04 0.03 0.06"),
                                       ("-1.57 0 0", "0.04 0.06 0.03")])
def test_a_box_caster_on_a_fixed_joint_keeps_the_robot_level(tmp_path, rpy, size):
    r"""``dd_robot.urdf`` with its caster ball replaced by a box reaching the ground, as a
    TurtleBot3 Burger's ``caster_back_link`` is (a collision box on a fixed joint, turned by
    rpy -1.57): ``pitch = false``, the caster named (a probe's TurtleBot3 was read as a
    balancing robot, nothing said). The same box lifted off the ground is no caster."""
    from pathlib import Path
    text = (Path(__file__).parent / "data" / "published" / "dd_robot.urdf").read_text()
    sphere = '<collision><geometry><sphere radius="0.03"/></geometry></collision>'
    assert text.count(sphere) == 1
    box = (f'<collision><origin rpy="{rpy}"/><geometry><box size="{size}"/></geometry>'
           '</collision>')
    text = text.replace(sphere, box).replace('<visual><geometry><sphere radius="0.03"/>',
                                             f'<visual><geometry><box size="{size}"/>')
    for lift, level in ((0.0, True), (0.05, False)):
        urdf = tmp_path / f"box_{lift}.urdf"
        urdf.write_text(text.replace(box, box.replace(
            '<origin rpy=', f'<origin xyz="0 0 {lift}" rpy=')))
        out = tmp_path / f"robot_{lift}.toml"
        assert main(["model", str(urdf), "--out", str(out)]) == 0
        line = next(x for x in out.read_text().splitlines() if x.startswith("pitch"))
        assert line.startswith(f"pitch = {str(not level).lower()}"), (lift, line)
        assert ("caster_link" in line) is level, line


def test_a_urdf_fixed_to_the_world_is_a_fixed_base_whatever_its_wheels(tmp_path, capsys):
    r"""A URDF whose massless root link is named ``world`` (ROS and Gazebo read it as the world
    itself) is a fixed base even where two links look like a wheel pair: the starter must not
    lock the cart's prismatic joint and make the world a rolling body. Its model has the
    hand-written model's inertia and gravity terms (the project's own test data,
    ``tests/data/wheeled_cart_pole``), at random configurations."""
    import pinocchio as pin
    from pathlib import Path
    folder = Path(__file__).parent / "data" / "wheeled_cart_pole"
    out = tmp_path / "robot.toml"
    assert main(["model", str(folder / "wheeled_cart_pole.urdf"), "--out", str(out)]) == 0
    said = capsys.readouterr().out
    assert "fixed to the world (its root link is 'world')" in said
    assert 'type = "fixed"' in out.read_text() and "joints.locked" not in out.read_text()
    mine, written = (load_model(str(p)).model for p in (out, folder / "wheeled_cart_pole.toml"))
    assert mine.nv == written.nv == 4
    rng = np.random.default_rng(SEED)
    for _ in range(N_STATES):
        q = pin.integrate(written, pin.neutral(written), rng.uniform(-1.0, 1.0, written.nv))
        v = rng.normal(size=written.nv)
        for model in (mine, written):
            assert [model.names[i] for i in range(1, model.njoints)] == \
                [written.names[i] for i in range(1, written.njoints)]
        pairs = [(pin.crba(m, m.createData(), q), pin.rnea(m, m.createData(), q, v,
                                                          np.zeros(m.nv))) for m in (mine, written)]
        for a, b in zip(*pairs):
            assert np.abs(a - b).max() <= TERMS_TOL * max(np.abs(b).max(), 1.0)


def test_a_fixed_base_starter_offers_its_inputs_and_they_load(tmp_path):
    r"""A base without wheels gets ``actuated`` and ``inputs`` commented out (B's columns):
    uncommented, the model has one input per moving joint, named as written."""
    out = tmp_path / "arm.toml"
    assert main(["model", str(urdf_dir() / "rod_pendulum.urdf"), "--out", str(out)]) == 0
    text = out.read_text()
    assert "# actuated = [" in text and "# inputs = [" in text
    assert load_model(str(out)).model.nv >= 1
    out.write_text(text.replace("# actuated = [", "actuated = [").replace("# inputs = [",
                                                                           "inputs = ["))
    wm = load_model(str(out))
    assert len(wm.input_names) == wm.model.nv, wm.input_names
