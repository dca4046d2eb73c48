r"""The textbook rolling disk (``literature/rolling_disk_euler_angles.toml``, model
``rolling_coin``): the reduced equations in heading psi, lean theta (positive to the left) and
spin phi, and their linearisation about upright straight rolling.

- As written, every element of the equations of motion and every linearised relation agrees,
  under the file's own reading of its maps (no other sign convention is needed). At the URDF's
  own parameters (a uniform thin disk) the document's A, h, Q equal the reduced truth exactly,
  without the engine.
- One planted error in one printed term makes exactly that element differ. The planted errors
  are a sign flip, a factor 2, a sin written for a cos, a dropped gyroscopic term, and a wrong
  sign in the linearised equations. Every other element still agrees.
- Correct rewrites are still judged right: a row multiplied through by a constant (undeclared
  2, or 1/m declared under ``[rows]``), trigonometry rewritten with double angles, the
  linearised relation divided through, and the whole file in the opposite lean sign convention
  with its map changed to match.
- The lean sign of the map matters. Flipped alone, the declared reading differs. The engine
  then finds the equivalent spin flip, because (theta, phi) -> (-theta, -phi) is a symmetry of
  the equations, and the linearised step differs.
- The file's linearised equations give the critical speed of upright rolling,
  Omega^2 = m g r I / (J (J + m r^2)); for the thin disk this is v^2 = g r / 3. The file states
  it as a ``critical speed`` step, which agrees with the one found on the true linearisation.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from conftest import SEED
from shipped_copies import rewritten_copy
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.grid.grid import derivation_coordinate_set
from wheeled_dyn.compare.sides.document import model_value
from wheeled_dyn.compare.grid.samples import ParameterSet, namespace_values
from wheeled_dyn.constraints import CoordinateMap
from wheeled_dyn.derivations import builtin_derivations, builtin_groups, load_derivation
from wheeled_dyn.models.registry import load_model

#: Engine grid (verdicts, not statistics).
SAMPLES, PARAM_SETS = 40, 2
#: Agreement of a document element with the reduced truth at the URDF's own parameters,
#: relative to (1 + the largest element of the truth's row).
AGREE_TOL = 1e-9
#: States for the check at the URDF's parameters.
N_STATES = 12
#: The lean drawn where the disk stands above its contact (the file's declared range).
LEAN_RANGE = (-1.3, 1.3)

GROUP = "literature"
FILE = "rolling_disk_euler_angles.toml"
#: Keys of the equations-of-motion records.
EOM_KEYS = ("A", "C", "Q", "B", "h", "G")
#: The equations-of-motion elements the file gives: A 3x3, Q 3, h 3 rows x 6 velocity products.
PRODUCTS = ("dpsi*dpsi", "dpsi*dtheta", "dpsi*dphi", "dtheta*dtheta", "dtheta*dphi",
            "dphi*dphi")
EOM_ELEMENTS = ({f"A[{i},{j}]" for i in (1, 2, 3) for j in (1, 2, 3)}
                | {f"Q[{i}]" for i in (1, 2, 3)}
                | {f"h[{i}]:{p}" for i in (1, 2, 3) for p in PRODUCTS})
STEP = "upright straight rolling linearised equations relation {}"

LEAN_ROW = ("(I + m*r**2)*ddtheta + (J + m*r**2)*cos(theta)*dpsi*dphi - (J + m*r**2 - I)"
            "*sin(theta)*cos(theta)*dpsi**2 - m*g*r*sin(theta) = 0")

#: The file in the opposite lean convention (theta positive to the right of the direction of
#: travel): the lean is the model's phi itself. The rows are the true rows of the new
#: coordinates. The lean row is written with its leading coefficient positive.
OPPOSITE_MAP = (
    'configuration = { psi = "psi", phi = "-theta", theta = "phi", z = "r*cos(theta)" }\n'
    'velocity_map = { dpsi = "dpsi", dtheta = "-dphi", dphi = "dtheta" }',
    'configuration = { psi = "psi", phi = "theta", theta = "phi", z = "r*cos(theta)" }\n'
    'velocity_map = { dpsi = "dpsi", dtheta = "dphi", dphi = "dtheta" }')
OPPOSITE_ROWS = [
    ("- (J + m*r**2)*sin(theta)*ddphi", "+ (J + m*r**2)*sin(theta)*ddphi"),
    ("- J*cos(theta)*dtheta*dphi", "+ J*cos(theta)*dtheta*dphi"),
    ("+ (J + m*r**2)*cos(theta)*dpsi*dphi", "- (J + m*r**2)*cos(theta)*dpsi*dphi"),
    ("(ddphi - sin(theta)*ddpsi) - (J + 2*m*r**2)", "(ddphi + sin(theta)*ddpsi) + (J + 2*m*r**2)"),
    ("I*ddpsi - J*Omega*dtheta", "I*ddpsi + J*Omega*dtheta"),
    ("+ (J + m*r**2)*Omega*dpsi", "- (J + m*r**2)*Omega*dpsi"),
]


def _source():
    return next(p for p in builtin_derivations(GROUP) if p.name == FILE)


def _copy(tmp_path, *replacements: tuple[str, str]):
    return rewritten_copy(_source(), tmp_path, *replacements)


def _compare(path):
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))


def _verdicts(result) -> dict[str, str]:
    return {r.element: r.verdict for r in result.records}


def _assert_all_agree(result):
    assert {r.element for r in result.records if r.key in EOM_KEYS} == EOM_ELEMENTS
    assert {STEP.format(k) for k in (1, 2, 3)} <= set(_verdicts(result))
    bad = {r.element: (r.verdict, r.texts) for r in result.records if r.verdict != "agrees"}
    assert not bad, bad
    # under the file's own reading of its maps: no other sign convention was needed
    assert result.conventions.best is None
    assert result.conventions.declared.counts["differs"] == 0


@pytest.fixture(scope="module")
def as_written():
    return _compare(_source())


def test_the_file_is_in_the_literature_group():
    assert GROUP in builtin_groups()
    assert FILE in [p.name for p in builtin_derivations(GROUP)]
    d = load_derivation(_source())
    assert d.model == "rolling_coin"
    assert [str(p) for p in d.positions] == ["psi", "theta", "phi"]
    assert d.form == "equations" and len(d.equations) == 3
    assert [s.kind for s in d.steps] == ["linearised equations", "critical speed"]


def test_as_written_every_element_agrees(as_written):
    _assert_all_agree(as_written)
    eom = [r for r in as_written.records if r.key in EOM_KEYS]
    assert len(eom) == len(EOM_ELEMENTS) == 30
    assert all(r.step == "equations of motion" for r in eom)
    steps = [r for r in as_written.records if r.key == "step"]
    assert [r.equation for r in steps] == ["upright straight rolling"] * 3 + ["critical speed"]
    assert [r.step for r in steps] == ["linearised equations"] * 3 + ["critical speed"]


def test_exact_at_the_urdf_parameters():
    r"""Without the engine: the document's A, h, Q at the URDF's own thin disk equal the
    reduced truth of the file's coordinate map (Pinocchio, rolling eliminated)."""
    d = load_derivation(_source())
    wm = load_model(d.model)
    ps = ParameterSet(wm, namespace_values(wm, None))
    cmap = CoordinateMap(wm, derivation_coordinate_set(d, ps))
    values = {s.symbol: model_value(s.value, ps.values) for s in d.symbols.values()
              if s.value is not None}
    doc = d.read_off(unscale=True)
    parts = {k: sp.lambdify([d.positions, d.velocities], sp.Matrix(M).xreplace(values))
             for k, M in (("A", doc.A), ("Q", doc.Q), ("h", doc.h))}
    rng = np.random.default_rng(SEED)
    for _ in range(N_STATES):
        q = rng.uniform(-np.pi, np.pi, 3)
        q[1] = rng.uniform(*LEAN_RANGE)
        nu = rng.normal(size=3) * [1.0, 1.0, 6.0]
        truth = cmap.terms(q, nu)
        for key, fn in parts.items():
            T = getattr(truth, key)
            D = np.array(fn(q, nu), dtype=float).reshape(T.shape)
            row = np.abs(T).reshape(3, -1).max(axis=1)
            err = np.abs(D - T).reshape(3, -1) / (1 + row[:, None])
            assert err.max() < AGREE_TOL, (key, q, nu, err)


@pytest.mark.parametrize("old, new, element, diagnosis", [
    ("- m*g*r*sin(theta) = 0", "+ m*g*r*sin(theta) = 0", "Q[2]", "sign"),
    ("2*(J + m*r**2 - I)", "(J + m*r**2 - I)", "h[1]:dpsi*dtheta", "factor: the document is 1/2"),
    ("(J + 2*m*r**2)*cos(theta)", "(J + 2*m*r**2)*sin(theta)", "h[3]:dpsi*dtheta",
     "swap: sin(theta) where cos(theta) fits"),
    ("- (J + m*r**2)*sin(theta)*ddphi", "- (J + m*r**2)*cos(theta)*ddphi", "A[1,3]",
     "swap: cos(theta) where sin(theta) fits"),
    (" + (J + m*r**2)*cos(theta)*dpsi*dphi", "", "h[2]:dpsi*dphi", "missing"),
    (" - J*cos(theta)*dtheta*dphi", "", "h[1]:dtheta*dphi", "missing"),
    ("+ (J + m*r**2)*Omega*dpsi", "- (J + m*r**2)*Omega*dpsi", STEP.format(2), "term dpsi: sign"),
    ("*dpsi - m*g*r*theta = 0", "*dpsi = 0", STEP.format(2), "term theta: missing"),
    ('"I*ddpsi - J*Omega*dtheta = 0"', '"I*ddpsi = 0"', STEP.format(1), "term dtheta: missing"),
], ids=["gravity-sign", "coriolis-factor-2", "sin-for-cos-h", "cos-for-sin-A",
        "dropped-gyroscopic-lean", "dropped-gyroscopic-heading", "linearised-sign",
        "linearised-dropped-gravity", "linearised-dropped-gyroscopic"])
def test_a_planted_error_differs_alone(tmp_path, as_written, old, new, element, diagnosis):
    result = _compare(_copy(tmp_path, (old, new)))
    verdicts = _verdicts(result)
    assert verdicts[element] == "differs"
    others = {e: v for e, v in verdicts.items() if e != element and v != "agrees"}
    assert not others, others
    assert set(verdicts) == set(_verdicts(as_written))
    assert result.conventions.best is None
    if diagnosis is not None:
        record = next(r for r in result.records if r.element == element)
        assert any(x.startswith(diagnosis) for x in record.texts), record.texts


@pytest.mark.parametrize("replacements", [
    # the lean row multiplied through by 2, undeclared (a constant row factor)
    [(LEAN_ROW, "2*(I + m*r**2)*ddtheta + 2*(J + m*r**2)*cos(theta)*dpsi*dphi - 2*(J + m*r**2 - I)"
                "*sin(theta)*cos(theta)*dpsi**2 - 2*m*g*r*sin(theta) = 0")],
    # the lean row divided through by m, declared
    [(LEAN_ROW, "(I/m + r**2)*ddtheta + (J/m + r**2)*cos(theta)*dpsi*dphi - (J/m + r**2 - I/m)"
                "*sin(theta)*cos(theta)*dpsi**2 - g*r*sin(theta) = 0"),
     ("[matrices]", '[rows]\nscale = ["1", "1/m", "1"]\n\n[matrices]')],
    # double angles: sin cos = sin(2 theta)/2, cos^2 = (1 + cos(2 theta))/2, sin^2 = ...
    [("(I*cos(theta)**2 + (J + m*r**2)*sin(theta)**2)*ddpsi",
      "(I*(1 + cos(2*theta))/2 + (J + m*r**2)*(1 - cos(2*theta))/2)*ddpsi"),
     ("2*(J + m*r**2 - I)*sin(theta)*cos(theta)*dpsi*dtheta",
      "(J + m*r**2 - I)*sin(2*theta)*dpsi*dtheta"),
     ("(J + m*r**2 - I)*sin(theta)*cos(theta)*dpsi**2", "(J + m*r**2 - I)*sin(2*theta)/2*dpsi**2")],
    # the linearised heading relation divided through by I
    [("I*ddpsi - J*Omega*dtheta = 0", "ddpsi = J/I*Omega*dtheta")],
    # the opposite lean sign convention, the map changed to match
    [OPPOSITE_MAP, *OPPOSITE_ROWS],
], ids=["row-times-2", "row-over-m-declared", "double-angles", "linearised-divided",
        "opposite-lean-convention"])
def test_a_correct_rewrite_still_agrees(tmp_path, replacements):
    _assert_all_agree(_compare(_copy(tmp_path, *replacements)))


def test_the_lean_sign_of_the_map_matters(tmp_path):
    r"""The map's lean flipped alone (the equations left in the left-positive convention): the
    declared reading differs. The equations cannot tell a lean flip from a spin flip, since
    (theta, phi) -> (-theta, -phi) leaves them unchanged, so the engine reads the file with
    the spin flipped. The linearised step is judged under the declared map and differs in its
    two gyroscopic couplings."""
    result = _compare(_copy(tmp_path, OPPOSITE_MAP))
    conv = result.conventions
    assert conv.declared.counts["differs"] > 0
    assert conv.best is not None and conv.best.counts["differs"] == 0
    assert "theta = -phi" in conv.best.description
    verdicts = _verdicts(result)
    assert verdicts[STEP.format(1)] == verdicts[STEP.format(2)] == "differs"
    assert verdicts[STEP.format(3)] == "agrees"


def test_critical_speed_from_the_linearised_equations():
    r"""From the file's linearised relations: psi' = (J Omega / I) theta after a lean
    disturbance from straight rolling (relation 1 integrated), then the lean's stiffness in
    relation 2 changes sign at Omega^2 = m g r I / (J (J + m r^2)), so v^2 = g r / 3 for
    the uniform thin disk (and at the URDF's coin)."""
    d = load_derivation(_source())
    step, stated = d.steps
    (lhs1, rhs1), (lhs2, rhs2), _ = step.sides
    psi, theta, phi = d.positions
    dpsi, dtheta, dphi = d.velocities
    ddpsi, ddtheta, ddphi = d.accelerations
    sym = {name: s.symbol for name, s in d.symbols.items()}
    m, r, g, I, J, Omega = (sym[k] for k in ("m", "r", "g", "I", "J", "Omega"))
    rel1, rel2 = sp.expand(lhs1 - rhs1), sp.expand(lhs2 - rhs2)
    # relation 1 is a ddpsi + b dtheta = 0: integrated from straight rolling, dpsi = -b/a theta
    a, b = rel1.coeff(ddpsi), rel1.coeff(dtheta)
    assert sp.expand(rel1 - a * ddpsi - b * dtheta) == 0
    lean = sp.expand(rel2.subs(dpsi, -b / a * theta))
    stiffness = sp.simplify(lean.coeff(theta) / lean.coeff(ddtheta))
    assert sp.expand(lean - lean.coeff(ddtheta) * ddtheta - lean.coeff(theta) * theta) == 0
    (critical,) = sp.solve(sp.Eq(stiffness, 0), Omega ** 2, dict=True)
    crit2 = critical[Omega ** 2]
    assert sp.simplify(crit2 - m * g * r * I / (J * (J + m * r ** 2))) == 0
    assert sp.simplify(stated.components[0] ** 2 - crit2) == 0      # the file's stated result
    thin = {I: m * r ** 2 / 4, J: m * r ** 2 / 2}
    assert sp.simplify((crit2.subs(thin) * r ** 2) - g * r / 3) == 0
    # the URDF's coin is that thin disk
    wm = load_model(d.model)
    values = namespace_values(wm, None)
    coin = {s.symbol: model_value(s.value, values) for s in d.symbols.values()
            if s.value is not None}
    assert np.isclose(float(coin[I]), float(coin[m]) * float(coin[r]) ** 2 / 4, rtol=1e-12)
    assert np.isclose(float(coin[J]), float(coin[m]) * float(coin[r]) ** 2 / 2, rtol=1e-12)


def test_steps_are_read_under_the_files_assumptions(tmp_path):
    r"""Without their own ``given``, the linearised relations and the critical speed are read
    under the file's ``[assumes]`` (the disk keeps its proportions): they still agree, and no
    "agrees only if" repeats what the file states."""
    path = _copy(tmp_path, ('about = { theta = "0", dphi = "Omega" }\ngiven = ["urdf_proportions"]\n',
                            'about = { theta = "0", dphi = "Omega" }\n'),
                 ('speed = "dphi"\ngiven = ["urdf_proportions"]\n', 'speed = "dphi"\n'))
    _assert_all_agree(_compare(path))


def test_a_lean_range_past_flat_is_drawn_on_the_ground(tmp_path):
    r"""The file's lean range widened past ±π/2 (to ±1.6): there its centre height
    r cos(theta) sinks the disk (no motion of the model is there), and the special position
    ±π/2 lays it flat. Those states are drawn again, the notes say how many, and every
    element still agrees (the flat disk at ±π/2 stopped the run with "q (coin) = 0.0:
    expected a configuration where the wheel is not lying flat", naming no file)."""
    result = _compare(_copy(tmp_path, ("ranges = { theta = [-1.3, 1.3] }",
                                       "ranges = { theta = [-1.6, 1.6] }")))
    _assert_all_agree(result)
    assert not result.asymmetric        # A nearly singular near flat on both sides: not said
    assert any("drawn again: the coordinate map puts the wheel off the ground" in note
               for note in result.notes), result.notes


@pytest.mark.parametrize("change, said", [
    (("ranges = { theta = [-1.3, 1.3] }\n", ""), "ranges"),          # off the ground in part
    (('z = "r*cos(theta)"', 'z = "r*sin(theta)"'), "every drawn state"),      # everywhere
], ids=["no-ranges", "wrong-height"])
def test_a_map_off_the_ground_is_one_error_naming_it(tmp_path, change, said):
    r"""Without its lean ranges (the disk sunk beyond a right angle on much of the default
    range: asked for them), or with a centre height that is never the rim's lowest point:
    one error naming the file and its map."""
    from wheeled_dyn.errors import DerivationError
    path = _copy(tmp_path, change)
    with pytest.raises(DerivationError) as err:
        _compare(path)
    text = str(err.value)
    assert path.name in text and "coordinates.configuration" in text, text
    assert "off the ground" in text and said in text, text


POINT_MASS = [
    ('"(I*cos(theta)**2 + (J + m*r**2)*sin(theta)**2)*ddpsi - (J + m*r**2)*sin(theta)*ddphi + '
     '2*(J + m*r**2 - I)*sin(theta)*cos(theta)*dpsi*dtheta - J*cos(theta)*dtheta*dphi = 0"',
     '"m*r**2*sin(theta)**2*ddpsi - m*r**2*sin(theta)*ddphi + 2*m*r**2*sin(theta)*cos(theta)'
     '*dpsi*dtheta = 0"'),
    ('"(I + m*r**2)*ddtheta + (J + m*r**2)*cos(theta)*dpsi*dphi - (J + m*r**2 - I)*sin(theta)'
     '*cos(theta)*dpsi**2 - m*g*r*sin(theta) = 0"',
     '"m*r**2*ddtheta + m*r**2*cos(theta)*dpsi*dphi - m*r**2*sin(theta)*cos(theta)*dpsi**2 - '
     'm*g*r*sin(theta) = 0"'),
    ('"(J + m*r**2)*(ddphi - sin(theta)*ddpsi) - (J + 2*m*r**2)*cos(theta)*dpsi*dtheta = 0"',
     '"m*r**2*(ddphi - sin(theta)*ddpsi) - 2*m*r**2*cos(theta)*dpsi*dtheta = 0"')]


def test_a_point_mass_disk_is_explained_as_printed_not_as_another_row(tmp_path):
    r"""The disk taken as a point mass (I = J = 0 in its three equations): the heading row's
    inertia is then sin(theta) × the spin row's, the equations dependent. The heading row was
    explained as "the true equation of phi times" a function of the lean, beside the spin
    row read as that same true equation, and the document's own checks were skipped; now no
    two rows are read as multiples of one true equation, the heading row is compared as
    printed, and A is said not positive definite — but not asymmetric, as it is not as printed
    (the rows a constant frame divides are read back as printed for that)."""
    result = _compare(_copy(tmp_path, *POINT_MASS))
    assert result.equivalent is False
    kinds = [c.kind for c in result.causes]
    frames = [e.frame for e in result.equations]
    assert not any("true equation of" in f for f in frames), frames
    assert any("not positive definite" in a for a in result.asymmetric), result.asymmetric
    assert not any("≠" in a for a in result.asymmetric), result.asymmetric
    assert "convention" not in kinds or all(
        "true equation of" not in c.explanation for c in result.causes), result.causes
