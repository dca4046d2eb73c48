r"""A link declared uniform whose URDF prints its inertia rounded
(:mod:`wheeled_dyn.models.uniform_reading`): the uniform body's moment where the printed one is
it to its digits, and only then. The cart-pole of ``data/published`` (a uniform pole, every
form of R. V. Florian's equations, ``published_forms.py``) with its pole made 0.2 kg and
0.8 m long and its moments printed to six digits, ``iyy="0.0106667"`` for
:math:`mL^2/12 = 0.010666\overline6`, as a ROS URDF prints them: every form agrees where it
was "the document is 1.000001 × the truth", and a planted point mass still differs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import sympy as sp
import pytest

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.compare.records import DiagnosisKind
from wheeled_dyn.models.uniform_reading import half_unit, uniform_inertials

DATA = Path(__file__).parent / "data" / "published"
SAMPLES, PARAM_SETS = 200, 3

ROD = """<robot name="r"><link name="rod"><inertial><origin xyz="0 0 0.4"/>
<mass value="0.2"/><inertia ixx="{ixx}" ixy="{ixy}" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/>
</inertial></link></robot>"""


def _read(ixx: str, iyy: str, izz: str, ixy: str = "0") -> dict:
    text = ROD.format(ixx=ixx, iyy=iyy, izz=izz, ixy=ixy)
    import pinocchio as pin
    inertia = pin.Inertia(0.2, np.array([0.0, 0.0, 0.4]),
                          np.array([[float(ixx), float(ixy), 0], [float(ixy), float(iyy), 0],
                                    [0, 0, float(izz)]]))
    inertials = {"rod": tuple(inertia.toDynamicParameters())}
    return uniform_inertials(text, {"rod": (0.01, 0.8)}, inertials)


def test_half_a_unit_of_the_last_digit() -> None:
    assert half_unit("0.0106667") == pytest.approx(5e-8)
    assert half_unit("1e-5") == pytest.approx(5e-6)
    assert half_unit("0.025") == pytest.approx(5e-4)
    assert half_unit("abc") is None


def test_a_rounded_slender_rod_is_read_as_one() -> None:
    read = _read("0.0106667", "0.0106667", "0.00001")
    assert set(read) == {"rod"}
    import pinocchio as pin
    own = pin.Inertia.FromDynamicParameters(np.asarray(read["rod"][0]))
    exact = 0.2 * 0.8 ** 2 / 12
    assert own.inertia[0, 0] == pytest.approx(exact, rel=1e-15)
    assert own.inertia[1, 1] == pytest.approx(exact, rel=1e-15)
    assert own.inertia[2, 2] == pytest.approx(1e-5, rel=1e-15)      # printed to one digit
    assert own.mass == pytest.approx(0.2) and own.lever == pytest.approx([0, 0, 0.4])
    assert "ixx 0.0106667 as m L²/12" in read["rod"][1] and "izz" not in read["rod"][1]


@pytest.mark.parametrize("ixx, ixy", [
    ("0.01066666666666667", "0"),       # printed as the body's: nothing to read
    ("0.01080", "0"),                   # 1e-4 from the rod and the cylinder: neither
    ("0.0106667", "0.001"),             # products of inertia: not its principal moments
], ids=["exact", "another-body", "products"])
def test_no_reading(ixx: str, ixy: str) -> None:
    assert _read(ixx, ixx, "0.00001", ixy) == {}


def _rounded_cart_pole(tmp_path: Path) -> Path:
    urdf = (DATA / "cart_pole.urdf").read_text()
    for old, new in (('<origin xyz="0 0 0.5" rpy="0 0 0"/>\n      <mass value="0.3"/>',
                      '<origin xyz="0 0 0.4" rpy="0 0 0"/>\n      <mass value="0.2"/>'),
                     ('ixx="0.025" ixy="0" ixz="0" iyy="0.025"',
                      'ixx="0.0106667" ixy="0" ixz="0" iyy="0.0106667"'),
                     ('<visual><origin xyz="0 0 0.5"/><geometry><cylinder radius="0.01" '
                      'length="1.0"/>', '<visual><origin xyz="0 0 0.4"/><geometry><cylinder '
                      'radius="0.01" length="0.8"/>')):
        assert urdf.count(old) == 1, old
        urdf = urdf.replace(old, new)
    (tmp_path / "cart_pole.urdf").write_text(urdf)
    model = tmp_path / "cart_pole.toml"
    model.write_text((DATA / "cart_pole.toml").read_text())
    return model


@pytest.mark.parametrize("form", ["equations", "solved", "divided"])
def test_every_form_agrees_on_the_rounded_pole(tmp_path: Path, form: str) -> None:
    model = _rounded_cart_pole(tmp_path)
    path = P.write(tmp_path, "pole", form, None)
    path.write_text(path.read_text().replace(str(DATA / "cart_pole.toml"), str(model)))
    result = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is True, [t for e in result.equations for t in e.texts]
    assert any("link pole, declared uniform: its URDF inertia read as the uniform body's"
               in n for n in result.notes), result.notes


def _ambiguous_pole(tmp_path: Path, inertia: str, radius: bool = True) -> object:
    r"""The rounded cart-pole with the pole's moments printed 0.01067, the 0.8 m rod's
    m L²/12 and its 1 cm cylinder's m (3r² + L²)/12 both to four digits, and its axial
    moment the cylinder's m r²/2 = 0.00001 (read as the cylinder's), and the pole row's
    inertia written ``inertia`` (``radius``: the document names the pole's radius r)."""
    model = _rounded_cart_pole(tmp_path)
    urdf = tmp_path / "cart_pole.urdf"
    text = urdf.read_text()
    axial = 'iyy="0.0106667" iyz="0" izz="0.0"'
    assert text.count(axial) == 1
    urdf.write_text(text.replace(axial, 'iyy="0.01067" iyz="0" izz="0.00001"').replace(
        '"0.0106667"', '"0.01067"'))
    path = P.write(tmp_path, "pole", "equations", None)
    text = path.read_text().replace(str(DATA / "cart_pole.toml"), str(model))
    assert text.count("4*ddtheta*l**2*m/3") == 1
    text = text.replace("4*ddtheta*l**2*m/3", inertia)
    if radius:
        text = text.replace('g = {', 'r = { value = "radius(pole)", units = "m" }\ng = {')
    path.write_text(text)
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))


def test_the_uniform_cylinders_inertia_agrees_where_a_rods_is_as_near(tmp_path: Path) -> None:
    r"""The pole's inertia about its hinge as a uniform cylinder's,
    :math:`m(3r^2 + L^2)/12 + ml^2 = m(\tfrac43 l^2 + r^2/4)` (L = 2l): right."""
    result = _ambiguous_pole(tmp_path, "ddtheta*m*(4*l**2/3 + r**2/4)")
    assert result.equivalent is True, [t for e in result.equations for t in e.texts]


@pytest.mark.parametrize("radius", [True, False], ids=["r-named", "r-not-named"])
def test_a_slender_rods_inertia_for_the_cylinder_lacks_a_part_of_a_moment(
        tmp_path: Path, radius: bool) -> None:
    r"""The slender rod's :math:`\tfrac43 ml^2` for the cylinder: it lacks :math:`mr^2/4`,
    half the pole's own moment about its axis — a term of the formula, named as such (in the
    document's r where it names one, else as that part of the model's moment), not the pole
    taken as a point mass."""
    result = _ambiguous_pole(tmp_path, "4*ddtheta*l**2*m/3", radius)
    assert result.equivalent is False
    (a22,) = [r for r in result.records if r.element == "A[2,2]"]
    assert a22.verdict == "differs"
    assert DiagnosisKind.POINT_MASS not in [x.kind for x in a22.diagnoses], a22.diagnoses
    # truth − document as the numbers read it: m r²/4 with r = l/40 (the pole's proportions)
    assert sp.simplify(sp.sympify(a22.residual) - sp.sympify("l**2*m/6400")) == 0, a22.residual
    if radius:
        assert any(x.kind == DiagnosisKind.MISSING and "m*r**2/4" in x.text
                   for x in a22.diagnoses), a22.diagnoses


def test_the_axial_moment_for_the_swing_moment_is_given_no_false_name(tmp_path: Path) -> None:
    r"""The pole's hinge inertia written with the cylinder's axial moment,
    :math:`m(l^2 + r^2/2)`, for its moment about a diameter: it lacks :math:`ml^2/3 - mr^2/4`,
    which the pole's proportions, kept in every draw (r = l/40), make equal to a multiple of
    either length squared — "lacks 6397*m*r**2/12" and "Izz(pole) × 253/6 … a point mass"
    were said. No such coefficient names it, and no point mass."""
    result = _ambiguous_pole(tmp_path, "ddtheta*m*(l**2 + r**2/2)")
    assert result.equivalent is False
    (a22,) = [r for r in result.records if r.element == "A[2,2]"]
    assert a22.verdict == "differs"
    assert DiagnosisKind.POINT_MASS not in [x.kind for x in a22.diagnoses], a22.diagnoses
    for x in a22.diagnoses:
        if x.kind == DiagnosisKind.MISSING:
            for term in x.terms:
                c = sp.sympify(term).as_coeff_Mul()[0]
                assert abs(c.p) <= 24 and c.q <= 24, x


@pytest.mark.parametrize("multiplier", [sp.Rational(1, 2), sp.Integer(1),
                                        sp.Rational(253, 6)], ids=["half", "whole", "junk"])
def test_a_part_of_a_moment_is_no_point_mass(multiplier: sp.Rational) -> None:
    r"""A residual that is half a link's own moment (:math:`mr^2/4` of a cylinder whose
    axial moment is :math:`mr^2/2`, the acrobot's second link written as a slender rod) is
    named as that term left out of a formula where the document's symbols give it, and not
    named otherwise (with a link's proportions kept in every draw, a fraction of any of its
    moments fits); the whole moment is the link taken as a point mass; 253/6 of one is no
    number a body's inertia is missing times."""
    from types import SimpleNamespace

    from wheeled_dyn.compare.judge.named import _own_inertia
    from wheeled_dyn.compare.judge.own_inertia import point_mass_fit
    rng = np.random.default_rng(SEED)
    moment = rng.uniform(0.1, 1.0, 50)
    hit = point_mass_fit(float(multiplier) * moment, {"Ixx(link2)": moment}, [])
    if multiplier.q == 6:
        assert hit is None
        return
    assert hit == ("Ixx(link2)", multiplier)
    draft = SimpleNamespace(diagnoses=[])
    term = sp.Symbol("m") * sp.Symbol("r") ** 2 / 4
    assert _own_inertia(draft, hit, None) is (multiplier == 1)
    if multiplier == 1:
        (said,) = draft.diagnoses
        assert said.kind == DiagnosisKind.POINT_MASS and "link2 as a point mass" in said.text
        return
    assert draft.diagnoses == []
    assert _own_inertia(draft, hit, term) is True
    (said,) = draft.diagnoses
    assert said.kind == DiagnosisKind.MISSING and "lacks m*r**2/4" in said.text
    assert "point mass" not in said.text


def test_a_point_mass_pole_still_differs_on_the_rounded_pole(tmp_path: Path) -> None:
    model = _rounded_cart_pole(tmp_path)
    path = P.write(tmp_path, "pole", "equations", "point_mass")
    path.write_text(path.read_text().replace(str(DATA / "cart_pole.toml"), str(model)))
    result = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is False


def test_a_rod_printed_with_no_axial_moment_is_the_rods() -> None:
    r"""The same moments with the axial one printed 0 (a slender rod's, as the seed's rod
    pendulum prints it): the rod's m L²/12 is meant, not the cylinder's."""
    read = _read("0.01067", "0.01067", "0")
    assert "as m L²/12" in read["rod"][1], read


def test_a_rod_and_its_cylinder_within_the_digits_read_as_the_cylinder() -> None:
    r"""0.01067 is the 0.8 m rod's m L²/12 (0.0106667) and its 1 cm cylinder's
    m (3r² + L²)/12 (0.0106717) both, to four digits: read as the cylinder's, the body the
    URDF draws (left unread, a document writing the uniform cylinder it declares, exactly,
    was "12/5 × what fits" in m r²/4; the slender rod's formula is the approximation that
    leaves m r²/4 out)."""
    import pinocchio as pin
    read = _read("0.01067", "0.01067", "0.00001")
    assert "as m (3 r² + L²)/12" in read["rod"][1], read
    own = pin.Inertia.FromDynamicParameters(np.asarray(read["rod"][0]))
    cylinder = 0.2 * (3 * 0.01 ** 2 + 0.8 ** 2) / 12
    assert own.inertia[0, 0] == pytest.approx(cylinder, rel=1e-15)
    assert own.inertia[1, 1] == pytest.approx(cylinder, rel=1e-15)


def _pole_with_bob(tmp_path: Path) -> Path:
    r"""The rounded cart-pole with a disk (0.5 kg, r 0.4 m, 0.2 m thick, its transverse
    moment printed rounded, 0.0216667) fixed at the pole's tip: one rigid body, two links."""
    model = _rounded_cart_pole(tmp_path)
    urdf = (tmp_path / "cart_pole.urdf").read_text()
    bob = """  <link name="bob">
    <inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="0.5"/>
      <inertia ixx="0.0216667" ixy="0" ixz="0" iyy="0.0216667" iyz="0" izz="0.04"/></inertial>
    <visual><geometry><cylinder radius="0.4" length="0.2"/></geometry></visual>
  </link>
  <joint name="tip" type="fixed"><parent link="pole"/><child link="bob"/>
    <origin xyz="0 0 0.8" rpy="0 0 0"/></joint>
</robot>"""
    (tmp_path / "cart_pole.urdf").write_text(urdf.replace("</robot>", bob))
    return model


def test_only_the_links_declared_uniform_are_read(tmp_path: Path) -> None:
    r"""A link fixed to a declared-uniform one is put together again with it when the body is
    drawn, and keeps its inertia as printed: the reading is the declaration's, link by link
    (it was applied to every link of the body)."""
    from types import MappingProxyType

    from wheeled_dyn.models.geometry_apply import GeometryDraw, apply_geometry
    from wheeled_dyn.models.registry import load_model
    wm = load_model(str(_pole_with_bob(tmp_path)))
    body = wm.joint_id_of_link("pole")

    def inertia(uniform: frozenset[str]) -> np.ndarray:
        draw = GeometryDraw(MappingProxyType({}), MappingProxyType(
            {"pole": (1.0, 1.0), "bob": (1.0, 1.0)}), uniform)
        return apply_geometry(wm, draw).model.inertias[body].inertia
    none, pole, both = (inertia(frozenset(u)) for u in ((), ("pole",), ("pole", "bob")))
    rod = 0.2 * 0.8 ** 2 / 12 - 0.0106667
    disk = 0.5 * (3 * 0.4 ** 2 + 0.2 ** 2) / 12 - 0.0216667
    assert np.allclose(pole - none, np.diag([rod, rod, 0.0]), rtol=0, atol=1e-15)
    assert np.allclose(both - pole, np.diag([disk, disk, 0.0]), rtol=0, atol=1e-15)


def test_a_link_fixed_to_another_names_the_bodies_with_parameters(tmp_path: Path) -> None:
    r"""``M(bob)`` for the disk fixed to the pole: one error naming the body it belongs to and,
    as valid names, the bodies that have a mass of their own (the list held every name the
    model's lengths use, the refused one among them)."""
    from wheeled_dyn.derivations.errors import DerivationNameError
    model = _pole_with_bob(tmp_path)
    path = P.write(tmp_path, "pole", "equations", None)
    text = path.read_text().replace(str(DATA / "cart_pole.toml"), str(model))
    path.write_text(text.replace('[symbols]\n', '[symbols]\nmb = { value = "M(bob)", units = "kg" }\n'))
    with pytest.raises(DerivationNameError) as err:
        ComparisonEngine(samples=20, param_sets=1, seed=SEED).compare(load_derivation(path))
    text = str(err.value)
    assert "fixed to the rigid body named pole" in text and "valid: cart, pole" in text, text


@pytest.mark.parametrize("printed", ["0.0107", "0.010666"], ids=["three-digits", "cut"])
def test_three_digits_and_cut_values_are_read(printed: str) -> None:
    r"""A moment printed to three digits (0.0107 for the 0.8 m rod's 0.0106667, the 1 cm
    cylinder's 0.0106717 a unit off too: the cylinder's read), or cut rather than rounded: read
    where one body's value is within a unit of the last digit."""
    read = _read(printed, printed, "0.00001")
    if printed == "0.0107":
        assert "as m (3 r² + L²)/12" in read["rod"][1]   # the rod's and the cylinder's both
    else:
        assert "as m L²/12" in read["rod"][1]


def test_text_that_is_no_number_is_no_reading() -> None:
    r"""An ``rpy`` or a moment that is no number (an unexpanded xacro property, ``nan``) is
    left to the URDF's own checks: no reading, and no error from here."""
    text = ('<robot><link name="rod"><inertial><origin rpy="${pi} 0 0"/><mass value="0.2"/>'
            '<inertia ixx="${i}" iyy="nan" izz="0" ixy="0" ixz="0" iyz="0"/></inertial>'
            '</link></robot>')
    inertials = {"rod": (0.2, 0.0, 0.0, 0.08, 0.04, 0.0, 0.04, 0.0, 0.0, 0.0)}
    assert uniform_inertials(text, {"rod": (0.01, 0.8)}, inertials) == {}
    assert uniform_inertials(text.replace("${pi}", "0"), {"rod": (0.01, 0.8)}, inertials) == {}


def test_a_rod_whose_inertia_is_turned_by_a_right_angle_is_read() -> None:
    r"""The rod's tensor written about its own axes and turned onto the link's by
    ``<origin rpy="1.5708 0 0">`` (a ROS URDF's wheel or rod): each printed moment is read
    about the link axis the turn puts it on (the reading had been left out for any turn, and
    a right file declaring the link uniform differed by the rounding)."""
    import pinocchio as pin
    text = ROD.format(ixx="0.0106667", ixy="0", iyy="0.00001", izz="0.0106667").replace(
        '<origin xyz="0 0 0.4"/>', '<origin xyz="0 0 0.4" rpy="1.5708 0 0"/>')
    R = np.asarray(pin.rpy.rpyToMatrix(np.pi / 2, 0.0, 0.0)).round()
    tensor = R @ np.diag([0.0106667, 0.00001, 0.0106667]) @ R.T        # as the model turns it
    read = read_turned(text, tensor)
    assert set(read) == {"rod"}
    own = pin.Inertia.FromDynamicParameters(np.asarray(read["rod"][0]))
    exact = 0.2 * 0.8 ** 2 / 12
    assert np.diag(own.inertia) == pytest.approx([exact, exact, 1e-5], rel=1e-15)
    assert not read_turned(text.replace('rpy="1.5708 0 0"', 'rpy="0.3 0 0"'), tensor)


def read_turned(text: str, tensor: np.ndarray) -> dict:
    r"""The reading of the rod of ``text`` whose model holds the link-frame ``tensor``."""
    import pinocchio as pin
    inertia = pin.Inertia(0.2, np.array([0.0, 0.0, 0.4]), tensor)
    return uniform_inertials(text, {"rod": (0.01, 0.8)},
                             {"rod": tuple(inertia.toDynamicParameters())})


def _rod_model(folder: Path, moment: str) -> Path:
    r"""The shipped ``rod_pendulum`` (1.5 kg, 1 m, its cylinder 1 cm in radius) as a user's
    own model, its moments about x and y printed ``moment``."""
    from wheeled_dyn.models.registry import MODELS
    from wheeled_dyn.paths import urdf_dir
    text = (urdf_dir() / "rod_pendulum.urdf").read_text()
    old = 'ixx="0.125" ixy="0" ixz="0" iyy="0.125"'
    assert text.count(old) == 1
    (folder / "rod_pendulum.urdf").write_text(
        text.replace(old, f'ixx="{moment}" ixy="0" ixz="0" iyy="{moment}"'))
    model = Path(MODELS["rod_pendulum"].source).read_text()
    path = folder / "rod_pendulum.toml"
    path.write_text(model.replace('package = "wheeled-dyn"\n', "").replace(
        'name = "rod_pendulum"', f'name = "{folder.name}_rod"'))
    return path


@pytest.mark.parametrize("moment, unlike", [("0.125", False), ("0.1875", True)],
                         ids=["uniform", "ends-heavy"])
def test_a_link_declared_uniform_that_its_urdf_is_not_is_the_files_error(
        tmp_path: Path, moment: str, unlike: bool) -> None:
    r"""The uniform rod pendulum (Meriam's 4.4 as ``published_forms.ROD`` writes it, right
    for a uniform rod: :math:`\tfrac13 m l^2\ddot\theta + \tfrac12 mgl\sin\theta = 0`,
    ``[assumes] uniform = ["rod"]``) on a URDF whose rod prints its moments 1.5 × a uniform
    rod's (its mass towards the ends): the truth keeps the URDF's inertia, the document
    differs, and the first cause is the file's: the rod declared uniform is no uniform body of
    its cylinder (every body's moment listed). On the shipped URDF, no such cause."""
    model = _rod_model(tmp_path, moment)
    path = tmp_path / "rod.toml"
    path.write_text(P.ROD.format(gravity="m*g*l/2*sin(theta)").replace(
        'model = "rod_pendulum"', f'model = "{model}"'))
    result = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is (not unlike), result.equations
    said = [c.explanation for c in result.causes if c.kind.value == "file_error"]
    if not unlike:
        assert said == [], said
        return
    assert result.causes[0].explanation == said[0]
    assert said[0].startswith("the file declares rod uniform, but link rod's URDF moments "
                              "(ixx 0.1875, iyy 0.1875, izz 0) are no uniform body's of the "
                              "shapes it draws, of mass 1.5 kg (m r²/2 = 7.5e-05, "), said
    assert "m L²/12 = 0.125)" in said[0], said


@pytest.mark.parametrize("shapes, unlike", [
    ('<collision><geometry><sphere radius="0.03"/></geometry></collision>'
     '<visual><geometry><cylinder radius="0.01" length="0.8"/></geometry></visual>', False),
    ('<visual><geometry><box size="0.8 0.02 0.02"/></geometry></visual>', False),
    ('<visual><geometry><mesh filename="rod.stl"/></geometry></visual>', False),
    ('<visual><geometry><cylinder radius="0.01" length="0.5"/></geometry></visual>', True),
], ids=["sphere-beside-its-cylinder", "box", "mesh", "another-length"])
def test_a_link_is_no_uniform_body_only_unlike_every_shape_it_draws(shapes, unlike) -> None:
    r"""The 0.8 m rod of 0.2 kg printing m L²/12 = 0.0106667 (and 0 about its axis): a
    collision sphere at its tip beside its visual cylinder, or a box of its length, is a shape
    it is uniform in (a probe's
    cart-pole with a sphere at the pole's tip had "no uniform body's of its sphere"); a mesh
    has moments of its own (nothing said); a cylinder of another length is not."""
    import pinocchio as pin

    from wheeled_dyn.models.uniform_reading import unlike_uniform
    text = ROD.format(ixx="0.0106667", ixy="0", iyy="0.0106667", izz="0").replace(
        "</inertial>", "</inertial>" + shapes)
    inertia = pin.Inertia(0.2, np.array([0.0, 0.0, 0.4]), np.diag([0.0106667, 0.0106667, 0.0]))
    found = unlike_uniform(text, {"rod": tuple(inertia.toDynamicParameters())})
    assert (set(found) == {"rod"}) is unlike, found
