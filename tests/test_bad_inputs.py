r"""Model and API inputs that ended in tracebacks (issue 25), each now one clear project error
naming the place — or, for a mesh the dynamics do not need, a warning: a mesh file that does
not exist, ``up = [0, 0, 0]``, a 500-link chain, a ``<mimic>`` joint; the public API's
functions called with arguments of the wrong type or value; NaN or an infinity in a
derivation's matrix. The command line prints each as one line (exit code 2 for an error)."""

from __future__ import annotations

import inspect
import math
import os
import pickle
import random
import stat
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import sympy as sp

import wheeled_dyn as wd
from wheeled_dyn.derivations import load_derivation
from shipped_copies import own_wip_model
from wheeled_dyn.errors import (ArgumentError, DerivationError, InputFileError, LimitError,
                                ModelError, ModelWarning, StateError, UnknownNameError,
                                WheeledDynError)
from wheeled_dyn.models.urdf_checks import MAX_MOVING_JOINTS, _subtree_masses

#: The body's box of the shipped URDF, and a mesh in its place that does not exist.
BOX = '<geometry><box size="0.3 1.0 0.5"/></geometry>'
MISSING_MESH = '<geometry><mesh filename="meshes/body.stl"/></geometry>'
#: Largest difference of the mass matrices of the same body built twice.
SAME_TOL = 1e-12
#: The right wheel's joint, and the same joint made to mimic the left one.
RIGHT = '<joint name="wheel_right_joint" type="continuous">'
MIMIC = RIGHT + '\n    <mimic joint="wheel_left_joint" multiplier="1" offset="0"/>'


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "wheeled_dyn.cli.main", *args],
                          capture_output=True, text=True, timeout=300)


def _chain(folder: Path, links: int, moving: set[int] | None = None) -> Path:
    r"""A fixed-base model file of a chain of ``links`` links (revolute joints, or only those
    in ``moving``, the others fixed)."""
    inertial = ('<inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" '
                'iyz="0" izz="0.1"/></inertial>')
    parts = [f'<link name="l{i}">{inertial}</link>' for i in range(links)]
    for i in range(1, links):
        kind = "revolute" if moving is None or i in moving else "fixed"
        parts.append(f'<joint name="j{i}" type="{kind}"><parent link="l{i - 1}"/>'
                     f'<child link="l{i}"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>'
                     '<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>')
    (folder / "chain.urdf").write_text(f'<robot name="chain">{"".join(parts)}</robot>')
    model = folder / "chain.toml"
    model.write_text(f'name = "{folder.name}_chain"\n[urdf]\npath = "chain.urdf"\n'
                     '[base]\ntype = "fixed"\n')
    return model


# -- model inputs ----------------------------------------------------------------------------
@pytest.mark.parametrize("mesh", ["meshes/body.stl", "/nonexistent/meshes/body.stl",
                                  "file:///nonexistent/meshes/body.stl"])
def test_a_missing_mesh_is_a_warning_and_the_dynamics_are_the_same(tmp_path, mesh):
    r"""Relative, absolute or a ``file://`` address: one warning each (an absolute path or
    ``file://`` address was a ModelError, the mesh loader's "could not load resource")."""
    model, urdf = own_wip_model(tmp_path, (BOX, MISSING_MESH.replace("meshes/body.stl", mesh)))
    with pytest.warns(ModelWarning) as said:
        wm = wd.load_model(model)
    (message,) = [str(w.message) for w in said if issubclass(w.category, ModelWarning)]
    assert mesh in message and "link body" in message and str(urdf) in message
    reference = wd.load_model("wip")
    q = np.random.default_rng(7).uniform(-1, 1, reference.model.nq)
    A = pin.crba(wm.model, wm.model.createData(), q)
    A_ref = pin.crba(reference.model, reference.model.createData(), q)
    assert np.abs(A - A_ref).max() < SAME_TOL
    out = _cli("matrices", str(model))
    assert out.returncode == 0, out.stderr
    assert out.stderr.count("\n") == 1 and out.stderr.startswith("wheeled-dyn: warning: ")


def test_up_zero_in_a_model_file_names_the_file_line_and_key(tmp_path):
    model, _ = own_wip_model(tmp_path, model_replacements=(("up = [0.0, 1.0, 0.0]",
                                                             "up = [0, 0, 0]"),))
    line = next(k for k, text in enumerate(model.read_text().split("\n"), 1)
                if text.startswith("up = [0, 0, 0]"))
    with pytest.raises(InputFileError) as err:
        wd.load_model(model)
    assert err.value.path == model and err.value.line == line and "base.up" in str(err.value)
    out = _cli("matrices", str(model))
    assert out.returncode == 2 and out.stderr.count("\n") == 1
    assert f"{model}:{line}: base.up: expected a direction" in out.stderr


def test_up_zero_in_a_python_spec_is_a_model_error():
    from wheeled_dyn.models.builder import build_wheeled_model
    from wheeled_dyn.models.registry import model_spec
    from dataclasses import replace
    with pytest.raises(ModelError, match=r"up direction \(0.0, 0.0, 0.0\)"):
        build_wheeled_model(replace(model_spec("wip"), up=(0.0, 0.0, 0.0)))


def test_a_500_link_chain_is_refused_by_a_named_limit(tmp_path):
    model = _chain(tmp_path, 500)
    with pytest.raises(LimitError) as err:
        wd.load_model(model)
    assert err.value.value == 499 and str(MAX_MOVING_JOINTS) in err.value.limit
    assert "chain.urdf" in str(err.value)
    out = _cli("matrices", str(model))
    assert out.returncode == 2 and out.stderr.count("\n") == 1
    assert "moving joints = 499: expected at most 100" in out.stderr


def test_a_1000_link_chain_of_fixed_joints_is_built_without_recursion(tmp_path):
    model = _chain(tmp_path, 1000, moving={1, 500})
    wm = wd.load_model(model)
    assert wm.nv == 2
    # the root link is fixed to the world: the model carries the other 999 (1 kg each)
    assert math.isclose(pin.computeTotalMass(wm.model), 999.0, rel_tol=1e-12)


def test_subtree_masses_match_a_recursive_sum_on_random_trees():
    rng = random.Random(20261122)
    for _ in range(50):
        n = rng.randint(1, 40)
        parent_of = {f"l{i}": f"l{rng.randrange(i)}" for i in range(1, n)}
        mass = {f"l{i}": rng.choice([0.0, rng.uniform(0.1, 3.0)]) for i in range(n)}

        def below(link: str) -> float:
            return mass[link] + sum(below(c) for c, p in parent_of.items() if p == link)
        totals = _subtree_masses(mass, parent_of)
        for link in mass:
            assert math.isclose(totals[link], below(link), rel_tol=1e-12, abs_tol=1e-12)


def test_a_mimic_joint_is_refused_naming_it_and_its_line(tmp_path):
    model, urdf = own_wip_model(tmp_path, (RIGHT, MIMIC))
    with pytest.raises(InputFileError) as err:
        wd.load_model(model)
    assert err.value.path == urdf and err.value.line == urdf.read_text().count(
        "\n", 0, urdf.read_text().index(RIGHT)) + 1
    assert "'wheel_right_joint' mimics joint 'wheel_left_joint'" in str(err.value)
    out = _cli("matrices", str(model))
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and "mimic" in out.stderr


def test_a_locked_mimic_joint_is_honoured_or_refused(tmp_path):
    r"""Locked with its leader at values that follow the relation: built; else refused."""
    from wheeled_dyn.models.urdf_checks import check_mimic
    import xml.etree.ElementTree as ET
    text = ('<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
            '<joint name="lead" type="revolute"><parent link="a"/><child link="b"/></joint>'
            '<joint name="follow" type="revolute"><parent link="b"/><child link="c"/>'
            '<mimic joint="lead" multiplier="2" offset="0.1"/></joint></robot>')
    root = ET.fromstring(text)
    check_mimic("r.urdf", text, root, {"lead": 0.3, "follow": 0.7}, ("lead", "follow"))
    with pytest.raises(InputFileError, match="does not follow"):
        check_mimic("r.urdf", text, root, {"lead": 0.3, "follow": 0.6}, ("lead", "follow"))
    with pytest.raises(InputFileError, match="mimic joint is not modelled"):
        check_mimic("r.urdf", text, root, {"follow": 0.1}, ("follow",))


# -- the Python API --------------------------------------------------------------------------
def _builtin(group):
    from wheeled_dyn.derivations import builtin_derivations
    return builtin_derivations(group)


def _shipped() -> Path:
    return _builtin("seed001")[0]


def _nested(depth: int) -> sp.Expr:
    e = sp.Symbol("theta")
    for _ in range(depth):
        e = sp.sin(e)
    return e


def _rod(title: str = "rod", **matrices):
    return wd.compare("rod_pendulum", coordinates={"positions": ["theta"],
                                                   "configuration": {"theta": "theta"}},
                      symbols={"m": "4*MZ(rod)**2/(3*YY(rod))", "l": "-3*YY(rod)/(2*MZ(rod))",
                               "g": "g"}, assumes={"families": ["urdf_structure"]},
                      title=title, samples=50, param_sets=1, **matrices)


def _simulate(duration: float = 0.1, nu=(0.0, 0.5, 0.0)):
    from wheeled_dyn.simulate import simulate_fast
    wip = wd.load_model("wip")
    cs = wd.builtin_coordinate_set(wip, "seed001")
    q0 = np.zeros(wip.model.nq)
    return simulate_fast(wip, cs, q0, np.asarray(nu, float), duration=duration)


def test_a_title_longer_than_a_file_name_is_compared():
    m, l, g, theta = sp.symbols("m l g theta")
    result = _rod("x" * 1000, A=sp.Matrix([[m * l**2 / 3]]), C=sp.zeros(1, 1),
                  Q=sp.Matrix([m * g * l / 2 * sp.sin(theta)]))
    assert result.equivalent is True
    assert len(str(result.path)) < 200


def _raises_picklable(call, kind: type = WheeledDynError, *words: str) -> WheeledDynError:
    with pytest.raises(kind) as info:
        call()
    err = info.value
    back = pickle.loads(pickle.dumps(err))
    assert type(back) is type(err) and str(back) == str(err)
    for word in words:
        assert word in str(err), (word, str(err))
    return err


@pytest.mark.parametrize("call, kind, words", [
    (lambda: wd.load_model(123), ArgumentError, ["load_model(name=123)"]),
    (lambda: wd.load_model("a\0b.toml"), ArgumentError, ["NUL"]),
    (lambda: wd.load_model("nope"), UnknownNameError, ["unknown model 'nope'", "wip"]),
    (lambda: wd.load_model("wip", 5), ArgumentError, ["WipParameters"]),
    (lambda: wd.matrices(7), ArgumentError, ["matrices(model=7)"]),
    (lambda: wd.matrices("wip", phi="abc"), StateError, ["phi", "'abc'"]),
    (lambda: wd.matrices("wip", phi=float("nan")), StateError, ["phi", "nan"]),
    (lambda: wd.matrices("wip", phi=10**400), StateError, ["phi", "finite real"]),  # Overflow
    (lambda: wd.compare("rod_pendulum", symbols={sp.Symbol("m"): "M(rod)"}), ArgumentError,
     ["symbols", "strings"]),                                                  # TypeError
    (lambda: wd.matrices("wip", "nope"), UnknownNameError, ["coordinate set 'nope'"]),
    (lambda: wd.compare("wip", samples=0), ArgumentError, ["samples=0", "1 to 100,000"]),
    (lambda: wd.compare("wip", samples=float("nan")), ArgumentError, ["samples=nan"]),
    (lambda: wd.compare("wip", samples="10"), ArgumentError, ["samples='10'"]),
    (lambda: wd.compare("wip", samples=2000, param_sets=1000), LimitError, ["1,000,000"]),
    (lambda: wd.compare(5), ArgumentError, ["compare(model=5)"]),
    (lambda: wd.compare("wip", coordinate="seed001"), ArgumentError, ["coordinate=", "tables"]),
    (lambda: wd.CoordinateMap(7, None), ArgumentError, ["CoordinateMap(wm=7)", "load_model"]),
    (lambda: wd.CoordinateMap(wd.load_model("wip"), "seed001"), ArgumentError,
     ["CoordinateMap(cs='seed001')", "builtin_coordinate_set"]),
    # a probe's calls that were TypeError, RecursionError, OSError, MemoryError, OverflowError
    (lambda: _builtin(5), ArgumentError, ["builtin_derivations(group=5)", "seed001"]),
    (lambda: load_derivation(_shipped(), parameters=5), ArgumentError, ["parameters=5"]),
    (lambda: _rod(A=sp.Matrix([[_nested(200)]])), DerivationError, ["nested too deeply"]),
    (lambda: _simulate(duration=1e9), StateError, ["duration", "samples"]),
    (lambda: _simulate(nu=[0.0, 1e200, 0.0]), StateError, ["overflows"]),
    (lambda: wd.compare("rod_pendulum", coordinates=None, A=[[1]]), DerivationError,
     ["coordinates: expected a coordinate set"]),                 # it blamed "matrices"
    (lambda: wd.compare("rod_pendulum", coordinates="x", symbols={"m": object()}, A=[[1]]),
     DerivationError, ["symbols: expected a mapping"]),
])
def test_api_arguments_raise_the_projects_picklable_errors(call, kind, words):
    _raises_picklable(call, kind, *words)


@pytest.mark.parametrize("A, where", [
    (sp.Matrix([[sp.nan, 0, 0], [0, 1, 0], [0, 0, 1]]), "A[1,1]"),
    ([[1, 0, 0], [0, sp.oo * sp.Symbol("phi"), 0], [0, 0, 1]], "A[2,2]"),
    ([[1, 0, 0], [0, 1, 0], [0, 0, float("-inf")]], "A[3,3]"),
    ([[1, 0, 0], [0, "nan", 0], [0, 0, 1]], "A[2,2]"),
])
def test_nan_or_infinity_in_a_matrix_is_named_not_an_unknown_symbol(A, where):
    err = _raises_picklable(lambda: wd.compare("wip", coordinates="seed001", A=A),
                            DerivationError, where, "not a finite")
    assert "unknown symbol" not in str(err)


def test_nan_in_a_derivation_file_is_named(tmp_path):
    r"""TOML has ``nan`` and ``inf`` floats: one in a matrix is named, with its line."""
    path = tmp_path / "nan.toml"
    path.write_text('title = "t"\nmodel = "wip"\n[coordinates]\nuse = "seed001"\n'
                    "[matrices]\nA = [[1, 0, 0], [0, nan, 0], [0, 0, inf]]\n")
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    assert err.value.line == 6 and "A[2,2]: 'nan' is not a finite number" in str(err.value)


def test_every_exported_function_checks_its_arguments():
    r"""Each function ``wheeled_dyn`` exports refuses a number where its first argument is
    expected (a model, a function, a generator ...) with :class:`ArgumentError` naming it."""
    functions = [n for n in wd.__all__ if inspect.isfunction(getattr(wd, n))
                 and inspect.signature(getattr(wd, n)).parameters]
    assert {"load_model", "matrices", "full_terms", "simulate"} <= set(functions)
    from wheeled_dyn import api
    from wheeled_dyn.arguments import checked
    checked(api.compare)                 # exported as the package today; checkable as is
    for name in functions:
        fn = getattr(wd, name)
        parameters = inspect.signature(fn).parameters.values()
        required = [p for p in parameters if p.default is p.empty
                    and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
        first = next(iter(parameters)).name
        with pytest.raises(ArgumentError) as err:
            fn(7, *[None] * (len(required) - 1))
        assert err.value.function == name and err.value.name == first


@pytest.mark.parametrize("call, words", [
    (lambda wm: wd.full_terms(wm, np.zeros(2), np.zeros(6)), ["q=", "6 numbers"]),
    (lambda wm: wd.contact_jacobian(wm, "x"), ["q='x'", "vector"]),
    (lambda wm: wd.multipliers(wm, np.zeros(6), np.zeros(6), np.zeros(5)), ["u=", "2 numbers"]),
    (lambda wm: wd.christoffel_tensor(wm.model, np.zeros(2)), ["q=", "6 numbers"]),
    (lambda wm: wd.h_coefficients(lambda v: v, 0), ["n=0"]),
    (lambda wm: wd.random_wip_parameters(5), ["rng=5", "default_rng"]),
    (lambda wm: wd.simulate(wd.CoordinateMap(wm, wd.builtin_coordinate_set(wm)),
                            np.zeros(6), np.zeros(3), -1.0), ["duration=-1.0", "positive"]),
])
def test_wrong_vectors_and_numbers_are_named(call, words):
    wm = wd.load_model("wip")
    _raises_picklable(lambda: call(wm), ArgumentError, *words)


# -- files written ---------------------------------------------------------------------------
@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_reports_respect_the_umask_and_are_written_whole(tmp_path, umask, mode):
    from wheeled_dyn.report.write import write_reports
    old = os.umask(umask)
    try:
        paths = write_reports({"report.md": "# r\n", "report.json": "{}"}, tmp_path / "out")
    finally:
        os.umask(old)
    assert {stat.S_IMODE(p.stat().st_mode) for p in paths} == {mode}
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["report.json", "report.md"]


def test_a_folder_where_a_report_goes_leaves_the_old_reports_whole(tmp_path):
    r"""A folder named ``report.json`` where the reports go: one error naming it, and no report
    replaced (the Markdown and HTML ones were, then the error named a temporary file)."""
    from wheeled_dyn.report.write import write_reports
    out = tmp_path / "out"
    (out / "report.json").mkdir(parents=True)
    (out / "report.md").write_text("old")
    _raises_picklable(lambda: write_reports({"report.md": "new", "report.json": "{}"}, out),
                      InputFileError, "report.json", "directory")
    assert (out / "report.md").read_text() == "old"
    assert sorted(p.name for p in out.iterdir()) == ["report.json", "report.md"]


def test_a_full_disk_leaves_no_report_folder_behind(tmp_path, monkeypatch):
    r"""Reports into a new folder ``out/deep`` on a full disk (every write fails with
    ENOSPC): one error naming the file, and neither the folders made for them nor a
    temporary file left (the empty folder stayed)."""
    import errno
    from wheeled_dyn.report.write import write_reports

    def full(fd, *args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")
    monkeypatch.setattr(os, "fdopen", full)
    _raises_picklable(lambda: write_reports({"report.md": "# r", "report.json": "{}"},
                                            tmp_path / "out" / "deep"),
                      InputFileError, "report.md", "No space left")
    assert list(tmp_path.iterdir()) == []


def test_a_folder_given_as_a_model_is_named_so(tmp_path, monkeypatch):
    r"""A folder named where a model is expected (``adir``, as a name): "is a folder, expected
    a model file" (it was "names, or a model file path (name.toml): unknown model ...")."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "adir").mkdir()
    _raises_picklable(lambda: wd.load_model("adir"), InputFileError, "is a folder",
                      "model file")


def test_a_urdf_path_that_is_no_file_is_named_so(tmp_path):
    r"""A URDF path that is a FIFO (or a folder): "not a URDF file", where it said "no such
    URDF file"."""
    from wheeled_dyn.models.urdf_source import read_urdf
    fifo = tmp_path / "robot.urdf"
    os.mkfifo(fifo)
    _raises_picklable(lambda: read_urdf(fifo), InputFileError, "robot.urdf",
                      "not a URDF file")


def test_no_warning_from_a_shipped_model():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelWarning)
        wd.load_model("tiago_base")


def test_a_coordinate_table_without_positions_is_named(tmp_path):
    r"""``positions = []`` and no set named: one error naming ``coordinates.positions`` (it
    was an AttributeError)."""
    path = tmp_path / "empty.toml"
    path.write_text('title = "t"\nmodel = "wip"\n[coordinates]\npositions = []\n'
                    '[matrices]\nA = [[1]]\n')
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    assert "coordinates.positions" in str(err.value) and "at least one position" in str(err.value)


FLOATING_ROOT = """<?xml version="1.0"?>
<robot name="r">
  <link name="base_footprint"/>
  <joint name="base_footprint_joint" type="floating">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 0.1"/>
  </joint>
  <link name="base_link">
    <inertial><origin xyz="0 0 0.2"/><mass value="10"/>
      <inertia ixx="0.2" ixy="0" ixz="0" iyy="0.3" iyz="0" izz="0.4"/></inertial>
  </link>
""" + "".join(f"""  <joint name="{side}_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="{side}_wheel"/>
    <origin xyz="0 {y} 0"/><axis xyz="0 1 0"/>
  </joint>
  <link name="{side}_wheel">
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.1" length="0.04"/>
    </geometry></collision>
    <inertial><mass value="1"/>
      <inertia ixx="0.0026" ixy="0" ixz="0" iyy="0.005" iyz="0" izz="0.0026"/></inertial>
  </link>
""" for side, y in (("left", 0.2), ("right", -0.2))) + "</robot>\n"


def test_a_floating_root_joint_the_starter_locks_says_why_it_does_not_build(tmp_path):
    r"""A ROS URDF whose root joint is ``floating`` (written for the test): the starter model
    locks the joints between the root and the axle, and a joint of seven coordinates cannot
    be locked at one value — the message said "locked value 0.0: expected a finite number",
    a value the user never wrote. It names the joint and what to do."""
    from wheeled_dyn.models.starter import inspect_urdf
    from wheeled_dyn.models.starter_summary import summary
    path = tmp_path / "floating.urdf"
    path.write_text(FLOATING_ROOT)
    lines, builds = summary(inspect_urdf(path, ()))
    assert not builds
    (why,) = [line for line in lines if "does not build" in line]
    assert "base_footprint_joint" in why and "7 coordinates" in why and "fixed" in why, why
    assert "locked value 0.0" not in why


def test_a_model_without_a_moving_joint_says_so(tmp_path):
    r"""A model whose URDF has one link, nothing moving (written for the test): asked for its
    matrices, one error says it has no moving joint — it said "coordinate set 'full',
    positions: expected a non-empty list of names", a set the user never wrote."""
    from wheeled_dyn.errors import ModelError
    (tmp_path / "one.urdf").write_text(
        '<?xml version="1.0"?>\n<robot name="one"><link name="base_link"><inertial>'
        '<mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
        '</inertial></link></robot>\n')
    (tmp_path / "one.toml").write_text('name = "one"\n[urdf]\npath = "one.urdf"\n[base]\n'
                                       'type = "fixed"\nbody = "base_link"\n')
    _raises_picklable(lambda: wd.matrices(str(tmp_path / "one.toml")), ModelError,
                      "no moving joint")


def test_an_input_of_a_model_without_motors_says_where_motors_are_named(tmp_path):
    r"""A derivation with an input for a model file that names no motors (``wheeled-dyn
    model`` writes none for a fixed-base arm): one error naming the file, its line and the
    key, and where a model file names its motors."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    data = Path(__file__).parent / "data" / "two_link_arm"
    for name in ("two_link_arm.urdf",):
        (tmp_path / name).write_text((data / name).read_text())
    (tmp_path / "arm.toml").write_text('name = "arm_without_motors"\n[urdf]\n'
                                       'path = "two_link_arm.urdf"\n[base]\ntype = "fixed"\n')
    doc = tmp_path / "doc.toml"
    doc.write_text((data / "arm_lagrange.toml").read_text().replace(
        'model = "two_link_arm.toml"', 'model = "arm.toml"'))
    from wheeled_dyn.derivations.errors import DerivationNameError
    with pytest.raises(DerivationNameError) as err:
        ComparisonEngine(samples=20, param_sets=1).compare(load_derivation(doc))
    assert err.value.path == doc and err.value.item == "inputs.tau_1"
    said = str(err.value)
    assert str(doc) in said and "inputs." in said and "there are none" in said, said
    assert "[joints] actuated" in said, said


@pytest.mark.parametrize("name", ["elbow", "nolink"])
def test_a_joint_named_as_a_uniform_link_is_an_unknown_link(tmp_path, name):
    r"""``[assumes] uniform`` names links; a joint's name there (``elbow``: Pinocchio has a
    frame of that name, a joint's) is one error listing the links, as an unknown name is —
    it was taken, and the right file was "not right as a system"."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    from wheeled_dyn.errors import DerivationError
    data = Path(__file__).parent / "data" / "two_link_arm"
    for path in data.iterdir():
        (tmp_path / path.name).write_bytes(path.read_bytes())
    doc = tmp_path / "arm_lagrange.toml"
    doc.write_text(doc.read_text().replace('uniform = ["upper_arm", "forearm"]',
                                           f'uniform = ["upper_arm", "{name}"]'))
    with pytest.raises(DerivationError) as err:
        ComparisonEngine(samples=20, param_sets=1).compare(load_derivation(doc))
    said = str(err.value)
    assert err.value.path == doc and f"unknown link {name!r}" in said, said
    assert "valid: base, forearm, upper_arm" in said, said


@pytest.mark.parametrize("term, words", [("exp(m2)*dq1", "linear in the velocity dq1"),
                                         ("ddq1*ddq2", "not linear in the accelerations")])
def test_a_term_of_no_kind_names_its_equations_line(tmp_path, term, words):
    r"""A term in equation 2 that is no inertia, velocity, gravity or input term: one error
    naming the file, the line the equation is written on and the equation (the line was
    missing)."""
    from wheeled_dyn.errors import DerivationError
    data = Path(__file__).parent / "data" / "two_link_arm"
    for path in data.iterdir():
        (tmp_path / path.name).write_bytes(path.read_bytes())
    doc = tmp_path / "arm_lagrange.toml"
    lines = doc.read_text().splitlines()
    at = next(n for n, x in enumerate(lines, 1) if x.strip().startswith('"') and "tau2" in x)
    lines[at - 1] = lines[at - 1].replace(" = tau2", f" + {term} = tau2")
    doc.write_text("\n".join(lines) + "\n")
    with pytest.raises(DerivationError) as err:
        load_derivation(doc).read_off()
    said = str(err.value)
    assert err.value.line == at and f"{doc}:{at}: equation 2" in said and words in said, said


def test_a_urdf_given_as_the_model_file_says_how_to_write_one():
    r"""``wheeled-dyn matrices robot.urdf`` and ``wd.load_model("robot.urdf")``: one error
    saying a URDF is no model file and the command that writes one (it was "malformed TOML:
    Invalid statement", the URDF read as TOML)."""
    urdf = Path(__file__).parent / "data" / "ros_balancer" / "ros_balancer.urdf"
    with pytest.raises(InputFileError, match="a URDF is no model file") as err:
        wd.load_model(str(urdf))
    assert "wheeled-dyn model" in str(err.value)
    out = _cli("matrices", str(urdf))
    assert out.returncode == 2 and "a URDF is no model file" in out.stderr, out.stderr
