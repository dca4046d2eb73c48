r"""A quasi-velocity set that leaves a motion of the model free (:mod:`wheeled_dyn.constraints.held`).

Seed 001's pendulum pitches and turns. A level-body derivation in :math:`(v, \omega)` — the
differential drive's form (Dhaouadi & Abu Hatab, Adv. Robot. Autom. 2:107, 2013) — leaves its
pitch free; a planar one in :math:`(x, \phi)`, its heading. Where the file's configuration holds
that coordinate at a constant whose rate no velocity maps, the truth is the model with it held:
the rows of the full three-coordinate set's terms for the velocities kept, with the held rate
zero (an identity between two reductions: a different set of rolling equations solved). Before,
a pseudo-inverse filled the free rate in (the smallest velocity norm), a truth of no robot.
"""

from __future__ import annotations

import numpy as np
import pytest

from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model
from wheeled_dyn.coordinates.spec import CoordinateSpecError, parse_coordinate_set

SEED = 20261128
#: Agreement of two reductions of the same model (rounding of two pseudo-inverses).
TOL = 1e-10


def _set(wm, positions, velocities, configuration, velocity_map):
    return parse_coordinate_set(
        {"kind": "quasi", "rolling": "eliminate", "positions": positions,
         "velocities": velocities, "configuration": configuration,
         "velocity_map": velocity_map}, "test", wm.coordinate_names,
        tuple(wm.named_lengths()))


#: A derivation of seed 001's pendulum with its own quasi-velocity set and a diagonal A.
FILE = '''title = "{title}"
model = "wip"
[coordinates]
kind = "quasi"
positions = [{positions}]
configuration = {{ {configuration} }}
velocity_map = {{ {velocity_map} }}
[symbols]
m = {{ value = "m_S", units = "kg" }}
[matrices]
A = "{A}"
'''
#: The heading speed and rate as seed 001's set maps them.
HEADING = 'dx = "cos(psi)*dx0 + sin(psi)*dy0", dpsi = "dpsi"'


def _file(tmp_path, name: str, positions: list[str], **fields):
    r"""``FILE`` with ``fields``, A = m times the identity, written as ``name.toml``."""
    n = len(positions)
    A = "[" + ", ".join("[" + ", ".join("m" if i == j else "0" for j in range(n)) + "]"
                        for i in range(n)) + "]"
    path = tmp_path / f"{name}.toml"
    path.write_text(FILE.format(title=name, positions=", ".join(f'"{p}"' for p in positions),
                                A=A, **fields))
    return path


def _compare_file(path):
    from wheeled_dyn.compare import ComparisonEngine
    from wheeled_dyn.derivations import load_derivation
    return ComparisonEngine(samples=20, param_sets=1).compare(load_derivation(path))


def _file_error(path) -> str:
    from wheeled_dyn.errors import DerivationError
    with pytest.raises(DerivationError) as err:
        _compare_file(path)
    return str(err.value)


@pytest.mark.parametrize("kept, held, pitch", [
    ((0, 1), "phi", 0.3),          # (v, omega): the pitch held at 0.3 rad
    ((0, 2), "psi", 0.0),          # planar (x, phi): the heading held
])
def test_held_coordinate_is_the_full_set_with_its_rate_zero(kept, held, pitch):
    wm = load_model("wip")
    full = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))      # (x, psi, phi)
    names = ("x", "psi", "phi")
    positions = [names[k] for k in kept]
    config = {"x0": "x", "psi": "psi" if "psi" in positions else "0",
              "phi": "phi" if "phi" in positions else str(pitch)}
    vmap = {"dx": "cos(psi)*dx0 + sin(psi)*dy0", "dpsi": "dpsi", "dphi": "dphi"}
    cs = _set(wm, positions, ["d" + p for p in positions], config,
              {"d" + p: vmap["d" + p] for p in positions})
    part = CoordinateMap(wm, cs)
    assert part.held == (held,)
    rng = np.random.default_rng(SEED)
    for _ in range(5):
        q_full = rng.uniform(-1, 1, 3)
        q_full[names.index(held)] = pitch if held == "phi" else 0.0
        nu_full = rng.normal(size=3)
        nu_full[names.index(held)] = 0.0
        t_full = full.terms(q_full, nu_full)
        t_part = part.terms(q_full[list(kept)], nu_full[list(kept)])
        idx = np.ix_(kept, kept)
        np.testing.assert_allclose(t_part.A, t_full.A[idx], atol=TOL)
        np.testing.assert_allclose(t_part.h, t_full.h[list(kept)], atol=TOL)
        np.testing.assert_allclose(t_part.Q, t_full.Q[list(kept)], atol=TOL)
        np.testing.assert_allclose(t_part.B, t_full.B[list(kept)], atol=TOL)


def test_a_set_that_determines_every_motion_holds_nothing():
    wm = load_model("wip")
    assert CoordinateMap(wm, builtin_coordinate_set(wm, "seed001")).held == ()


def test_a_free_motion_no_constant_holds_is_refused_naming_it():
    wm = load_model("wip")
    # the pitch follows the distance travelled in the configuration, but no velocity maps
    # its rate: nothing holds it, and nothing determines it
    cs = _set(wm, ["x", "psi"], ["dx", "dpsi"], {"x0": "x", "psi": "psi", "phi": "x/10"},
              {"dx": "cos(psi)*dx0 + sin(psi)*dy0", "dpsi": "dpsi"})
    with pytest.raises(CoordinateSpecError, match=r"leave a motion of the model free.*phi"):
        CoordinateMap(wm, cs)


def test_a_planar_derivation_says_which_coordinate_it_holds():
    from wheeled_dyn.compare import ComparisonEngine
    from wheeled_dyn.derivations import builtin_derivations, load_derivation
    path = next(p for p in builtin_derivations("seed001") if p.name.startswith("report3_eq"))
    d = load_derivation(path)
    result = ComparisonEngine(samples=200, param_sets=2).compare(d)
    assert any("coordinate psi held at 0" in r for r in result.model_readings)


def test_a_files_free_motion_names_the_file_and_its_map(tmp_path):
    path = _file(tmp_path, "free", ["x", "psi"],                 # the pitch following x
                 configuration='x0 = "x", psi = "psi", phi = "x/10"', velocity_map=HEADING)
    text = _file_error(path)
    assert f"{path}:7" in text and "coordinates.velocity_map" in text, text
    assert "leave a motion of the model free" in text and "phi" in text, text


def test_a_velocity_map_that_is_not_linear_names_the_file_and_its_line(tmp_path):
    path = _file(tmp_path, "square", ["x", "psi", "phi"],
                 configuration='x0 = "x", psi = "psi", phi = "phi"',
                 velocity_map='dx = "dx0**2", dpsi = "dpsi", dphi = "dphi"')
    assert f"{path}:7: coordinates.velocity_map.dx: must be linear" in _file_error(path)


@pytest.mark.parametrize("kept, held, value", [((0, 1), "phi", "3/10"), ((0, 2), "psi", "0")])
def test_the_closed_forms_hold_it_as_the_numbers_do(kept, held, value):
    r"""The truth in the document's symbols (:func:`wheeled_dyn.symbolic.true_expressions`)
    of a set holding a coordinate: the full set's closed forms with it at its value and its
    rate zero (a probe's report showed Q[1] = -2 d g m_c/(3 r) beside a truth that agreed: the
    closed forms still took the smallest-norm rate)."""
    import sympy as sp

    from wheeled_dyn.symbolic import true_expressions
    wm = load_model("wip")
    full = true_expressions("wip", builtin_coordinate_set(wm, "seed001"))
    names = ("x", "psi", "phi")
    positions = [names[k] for k in kept]
    config = {"x0": "x", "psi": "psi" if "psi" in positions else "0",
              "phi": "phi" if "phi" in positions else value}
    vmap = {"dx": "cos(psi)*dx0 + sin(psi)*dy0", "dpsi": "dpsi", "dphi": "dphi"}
    cs = _set(wm, positions, ["d" + p for p in positions], config,
              {"d" + p: vmap["d" + p] for p in positions})
    part = true_expressions("wip", cs)
    assert full and part
    at = {sp.Symbol(held, real=True): sp.sympify(value), sp.Symbol("d" + held, real=True): 0}
    rng = np.random.default_rng(SEED)
    for key, expr in part.items():
        kind, rest = key[0], key[2:]
        if kind == "h":
            row, product = rest.split("]:")
            other = f"h[{kept[int(row) - 1] + 1}]:{product}"
        elif kind == "B":
            i, j = rest.rstrip("]").split(",")
            other = f"B[{kept[int(i) - 1] + 1},{j}]"
        else:
            idx = [kept[int(i) - 1] + 1 for i in rest.rstrip("]").split(",")]
            other = f"{kind}[{','.join(map(str, idx))}]"
        difference = sp.sympify(expr) - sp.sympify(full[other]).xreplace(at)
        free = sorted(difference.free_symbols, key=str)
        for _ in range(3):
            value_at = {s: float(rng.uniform(0.2, 1.2)) for s in free}
            assert abs(float(difference.xreplace(value_at))) <= TOL * 1e3, (key, difference)


def test_a_moving_coordinate_left_at_a_constant_the_truth_depends_on_is_refused(tmp_path):
    r"""A file mapping the pitch rate (``dtheta = "dphi"``) with the pitch left out of its
    configuration (so 0): the truth was computed at phi = 0 only, and a probe's equations with
    phi = 0 substituted (a small-angle model of a pitching robot) agreed. Its heading left at
    a constant is right (the truth does not depend on it: seed 001's sets leave y0 at 0)."""
    pitch = HEADING + ', dtheta = "dphi"'
    path = _file(tmp_path, "left_out", ["x", "psi", "theta"], configuration='psi = "psi"',
                 velocity_map=pitch)
    assert f"{path}:6: coordinates.configuration.phi: phi moves" in _file_error(path)
    path = _file(tmp_path, "left_out", ["x", "psi", "theta"],          # psi at 0: right
                 configuration='x0 = "x", phi = "theta"', velocity_map=pitch)
    assert _compare_file(path).equivalent is False          # (its A is no robot's; compared)
