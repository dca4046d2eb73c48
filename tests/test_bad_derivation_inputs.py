r"""Bad derivation files, ``simulate`` inputs and API arguments: one clear, picklable error of
the project's own, naming the file and the item, never a traceback of NumPy or SymPy, never a
hang (README "Bad input and limits")."""

from __future__ import annotations

import pickle
import subprocess
import sys
from pathlib import Path

import pytest

from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.other_documents.linear import is_linear_document
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import (ArgumentError, DerivationError, InputFileError, LimitError,
                                WheeledDynError)

#: A small valid file (the shipped rod pendulum in its mass and length); ``_write`` replaces
#: its lines.
ROD = '''title = "Uniform rod pendulum"
model = "rod_pendulum"
[coordinates]
positions = ["theta"]
configuration = { theta = "theta" }
[symbols]
m = { value = "M(rod)" }
l = { value = "length(rod)" }
g = "g"
[assumes]
uniform = ["rod"]
[matrices]
equations = ["1/3*m*l**2*ddtheta + m*g*l/2*sin(theta) = 0"]
'''
EQUATION = 'equations = ["1/3*m*l**2*ddtheta + m*g*l/2*sin(theta) = 0"]'


def _write(tmp_path: Path, old: str = "", new: str = "", text: str = ROD) -> Path:
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new) if old else text, encoding="utf-8")
    return path


def _clear(err: WheeledDynError, path: Path, *words: str) -> None:
    r"""``err`` names ``path`` and each of ``words``, and survives a pickle round trip."""
    text = str(err)
    assert str(path) in text, text
    for word in words:
        assert word in text, (word, text)
    again = pickle.loads(pickle.dumps(err))
    assert type(again) is type(err) and str(again) == text


def _equation(term: str) -> tuple[str, str]:
    return EQUATION, EQUATION.replace("sin(theta)", f"sin(theta)*{term}")


def test_a_key_of_the_file_written_under_source_is_named(tmp_path):
    r"""``convention = "unknown"`` written after the ``[source]`` table is, by TOML, a key of
    ``[source]``: the file was compared as declared, its report even advising to write it.
    Now one error says where it belongs."""
    path = _write(tmp_path, "[coordinates]",
                  '[source]\ndocument = "a textbook"\nconvention = "unknown"\n[coordinates]')
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    _clear(err.value, path, "source.convention", "above the first table")


# -- [coordinates] ---------------------------------------------------------------------------
def test_a_configuration_that_loses_a_position(tmp_path):
    path = _write(tmp_path, 'theta = "theta" }', 'theta = "0" }')
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    assert info.value.item == "coordinates.configuration"
    _clear(info.value, path, "'theta'", "Jacobian is singular")


@pytest.mark.parametrize("function", ["Abs", "sign"])
def test_a_configuration_without_a_derivative(tmp_path, function):
    path = _write(tmp_path, 'theta = "theta" }', f'theta = "{function}(theta)" }}')
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    assert info.value.item == "coordinates.configuration.theta"
    _clear(info.value, path, "coordinates.configuration.theta", "derivative")


@pytest.mark.parametrize("function", ["sqrt", "asin", "log"])
def test_a_configuration_not_finite_where_the_comparison_draws(tmp_path, function):
    path = _write(tmp_path, 'theta = "theta" }', f'theta = "{function}(theta)" }}')
    d = load_derivation(path)
    with pytest.raises(DerivationError) as info:
        ComparisonEngine(samples=20, param_sets=1).compare(d)
    assert info.value.item == "coordinates.configuration.theta"
    _clear(info.value, path, "not finite at theta = ", "ranges")


@pytest.mark.parametrize("pair", ["[-1e308, 1e308]", "[-inf, 0.0]", "[0.0, 1e200]"])
def test_ranges_finite_and_bounded(tmp_path, pair):
    path = _write(tmp_path, 'theta = "theta" }', f'theta = "theta" }}\nranges = {{ theta = {pair} }}')
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    _clear(info.value, path, "coordinates.ranges.theta", "finite")


@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "1e300"])
def test_linearised_about_finite_and_bounded(tmp_path, value):
    path = _write(tmp_path, 'uniform = ["rod"]',
                  f'uniform = ["rod"]\nlinearised_about = {{ theta = {value} }}')
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    _clear(info.value, path, "assumes.linearised_about.theta", "finite")


# -- expressions -----------------------------------------------------------------------------
@pytest.mark.parametrize("term, reason", [
    ("exp(1e99)", "argument"), ("cosh(1e50)", "argument"), ("sin(1e99)", "argument"),
    ("exp(exp(exp(10)))", "larger than"), ("exp(300)", "larger than"),
    ("(1e100)**(-64)", "smaller than"), ("(theta*1e100)**(-64)", "smaller than"),
    ("1e-5000", "smaller than"), ("9" * 5000, "larger than 1e+100")])   # (not Python's
def test_constants_numpy_cannot_compute_with(tmp_path, term, reason):   # 4300-digit limit)
    path = _write(tmp_path, *_equation(term))
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    assert info.value.item == "equation 1"
    _clear(info.value, path, "equation 1", reason)


def test_an_acceleration_in_C(tmp_path):
    path = _write(tmp_path, EQUATION, 'A = "[[m*l**2/3]]"\nC = "[[ddtheta]]"\n'
                                      'Q = "[m*g*l/2*sin(theta)]"')
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    assert info.value.item == "C[1,1]"
    _clear(info.value, path, "C[1,1]", "ddtheta", "positions and velocities only")


# -- the TOML itself -------------------------------------------------------------------------
@pytest.mark.parametrize("value", ["[" * 3000 + "]" * 3000, "{ a = " * 500 + "1" + " }" * 500])
def test_toml_nested_too_deeply(tmp_path, value):
    path = _write(tmp_path, text=ROD + f"\n[source]\nnotes = {value}\n")
    assert not is_linear_document(path)
    with pytest.raises(InputFileError) as info:
        load_derivation(path)
    _clear(info.value, path, "nested too deeply")


def test_many_symbols_do_not_hang(tmp_path):
    r"""20 000 symbols: one error at once, naming the limit (each symbol's value is parsed and
    checked; 20 000 that name model parameters took three minutes), and 1000 load."""
    from wheeled_dyn.derivations.limits import MAX_SYMBOLS
    code = ("import sys; from wheeled_dyn.derivations import load_derivation\n"
            "from wheeled_dyn.errors import DerivationError\n"
            "try: print(len(load_derivation(sys.argv[1]).symbols))\n"
            "except DerivationError as e: print(e)")
    for count, said in ((20_000, f"at most {MAX_SYMBOLS}"), (MAX_SYMBOLS - 3, str(MAX_SYMBOLS))):
        many = "\n".join(f's{i} = "g"' for i in range(count))
        path = _write(tmp_path, 'g = "g"', 'g = "g"\n' + many)
        done = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True,
                              text=True, timeout=60)
        assert done.returncode == 0, done.stderr
        assert said in done.stdout.strip(), done.stdout


# -- simulate --------------------------------------------------------------------------------
_SIMULATE = """
import pickle, sys
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import WheeledDynError
from wheeled_dyn.simulate.documented import side_by_side
try:
    side_by_side(load_derivation(sys.argv[1]), {}, 0.1, row_factors=(None,))
except WheeledDynError as err:
    print(type(err).__name__, str(pickle.loads(pickle.dumps(err))) == str(err), err)
"""


def test_simulate_a_document_with_imaginary_terms_stops(tmp_path):
    path = _write(tmp_path, "sin(theta) = 0", "sqrt(-1 - theta**2) = 0")
    done = subprocess.run([sys.executable, "-c", _SIMULATE, str(path)], capture_output=True,
                          text=True, timeout=60)
    kind, pickles, message = done.stdout.strip().split(" ", 2)
    assert (kind, pickles) == ("DerivationError", "True"), done.stderr
    assert str(path) in message and "equations" in message and "t = 0 s" in message


# -- the Python API --------------------------------------------------------------------------
@pytest.mark.parametrize("value", [5, None, 2.5, ["a.toml"]])
def test_load_derivation_of_a_non_path(value):
    with pytest.raises(ArgumentError) as info:
        load_derivation(value)
    assert "load_derivation(path=" in str(info.value) and "path" in info.value.expected
    assert str(pickle.loads(pickle.dumps(info.value))) == str(info.value)


def test_a_stray_character_is_named_not_the_space_before_it(tmp_path):
    r"""``m*g ? l`` in an equation: "token '?' is not allowed" (Python's tokenizer reports the
    space before a character it cannot read too, and the space was named)."""
    path = _write(tmp_path, "m*g*l/2*sin(theta)", "m*g ? l/2*sin(theta)")
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    _clear(info.value, path, "token '?' is not allowed")


def test_a_byte_order_mark_is_read_past(tmp_path):
    r"""A file saved by a Windows editor with a UTF-8 byte-order mark reads as without it (it
    was "1:1: malformed TOML: Invalid statement")."""
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + ROD.encode("utf-8"))
    assert load_derivation(path).title == "Uniform rod pendulum"


def test_comparing_a_loaded_derivation_checks_its_model_names(tmp_path):
    r"""``compare(load_derivation(path))`` as the command line does: a symbol valued by a name
    the model lacks is one error naming the file, the line and the item (a bare
    ``UnknownNameError`` without them, where a path was checked and a loaded file was not)."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    path = _write(tmp_path, 'm = { value = "M(rod)" }', 'm = { value = "inf" }')
    with pytest.raises(WheeledDynError) as info:
        ComparisonEngine(samples=20, param_sets=1).compare(load_derivation(path))
    _clear(info.value, path, "symbols.m.value", ":7:", "'inf'")


@pytest.mark.parametrize("kwargs, error, name", [
    ({"samples": 0}, ArgumentError, "samples"), ({"param_sets": -5}, ArgumentError, "param_sets"),
    ({"samples": 10 ** 7, "param_sets": 10 ** 4}, ArgumentError, "samples"),
    ({"samples": 100_000, "param_sets": 11}, LimitError, "samples × param_sets"),
    ({"samples": 2.5}, ArgumentError, "samples"), ({"seed": -1}, ArgumentError, "seed")])
def test_engine_grid_size_checked_as_the_cli_does(kwargs, error, name):
    with pytest.raises(error) as info:
        ComparisonEngine(**kwargs)
    assert info.value.name == name
    assert str(pickle.loads(pickle.dumps(info.value))) == str(info.value)


def test_engine_compares_a_path_and_refuses_anything_else(tmp_path):
    engine = ComparisonEngine(samples=20, param_sets=1)
    with pytest.raises(ArgumentError) as info:
        engine.compare(5)                              # type: ignore[arg-type]
    assert "ComparisonEngine.compare(d=5)" in str(info.value)
    path = _write(tmp_path)
    assert engine.compare(str(path)).equivalent


def test_a_map_using_a_symbol_of_a_centre_of_mass_names_that_symbol(tmp_path):
    r"""A coordinate map may use the model's lengths, not a centre of mass: the error names the
    symbol the map uses (``delta``), not the first declared one sharing its parameter (it
    named ``l_c``, which the map does not use)."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    text = ROD.replace('g = "g"', 'g = "g"\nl_c = { value = "sqrt(MX(rod)**2 + MZ(rod)**2)" }\n'
                       'delta = { value = "atan(MX(rod)/MZ(rod))" }').replace(
        'configuration = { theta = "theta" }', 'configuration = { theta = "theta + delta" }')
    path = _write(tmp_path, text=text)
    with pytest.raises(DerivationError) as err:
        ComparisonEngine(samples=20, param_sets=1).compare(load_derivation(path))
    _clear(err.value, path, "coordinates.configuration.theta", "the symbol delta is")


def test_a_wheel_joints_origin_is_named_by_the_axle(tmp_path):
    r"""The joints from a planar model's root to its wheels have no lengths of their own: the
    axle's height is R and half the track L. A symbol valued by one (a newcomer's COM height
    above the axle written ``CZ(base_link) - origin_z(left_wheel_joint)``) was "unknown joint"
    with a list of other joints; it now says why, and what to write."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    ros = Path(__file__).parent / "data" / "ros_balancer"
    (tmp_path / "ros_balancer.toml").write_text((ros / "ros_balancer.toml").read_text().replace(
        'path = "ros_balancer.urdf"', f'path = "{ros / "ros_balancer.urdf"}"'))
    text = (ros / "ros_balancer_heading.toml").read_text()
    old = 'z_b  = { value = "CZ(base_link)",'
    path = _write(tmp_path, old, 'z_b  = { value = "CZ(base_link) - origin_x(left_wheel_joint)",',
                  text=text)
    with pytest.raises(DerivationError) as err:
        ComparisonEngine(samples=20, param_sets=1).compare(load_derivation(path))
    _clear(err.value, path, "symbols.z_b.value", "origin_x(left_wheel_joint)",
           "joins the body to the wheels", "write them as numbers")


@pytest.mark.parametrize("body", ["k{p}*(k{p} + 1)", "sin(k{p})"])
@pytest.mark.parametrize("reverse", [False, True])
def test_definitions_nested_too_deeply(tmp_path, body, reverse):
    r"""``[definitions]`` each used in the next: 40 of ``k = j*(j + 1)`` (a tree of 2**40
    nodes SymPy's traversals visit) ran for minutes before the terms were counted; 400 of
    ``sin`` overflowed Python's stack (a traceback). Both, in either order, are one error
    naming the file and the definition, at once: too deep, or (the doubling body in the order
    declared) too large written out, which its fifteenth level is already."""
    defs = [f'k{i} = "{body.format(p=i - 1)}"' if i else 'k0 = "theta + m"' for i in range(400)]
    text = ROD.replace("[matrices]", "[definitions]\n" + "\n".join(
        reversed(defs) if reverse else defs) + "\n\n[matrices]").replace(
        "1/3*m*l**2*ddtheta", "(1/3*m*l**2 + 0*k399)*ddtheta")
    path = _write(tmp_path, text=text)
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    _clear(err.value, path, "definitions.k")
    assert "nested more than" in str(err.value) or "nodes written out" in str(err.value)


def test_a_loop_of_symbolic_links_is_one_error(tmp_path):
    r"""A derivation file, and a model file, that are links to themselves: one error naming
    the path (Python's ``RuntimeError: Symlink loop`` was a traceback)."""
    import wheeled_dyn as wd
    from wheeled_dyn.cli.main import main
    loop = tmp_path / "loop.toml"
    loop.symlink_to(loop)
    with pytest.raises(InputFileError) as err:
        wd.load_model(str(loop))
    _clear(err.value, loop, "loop")
    assert main(["compare", "rod_pendulum", str(loop)]) == 2
    assert main(["compare", str(loop), str(_write(tmp_path))]) == 2


def test_a_model_that_cannot_be_read_is_named_before_any_mismatch(tmp_path, capsys):
    r"""A derivation naming a file that is no model file (``model = "notes.txt"``): the error
    names the derivation, its ``model`` line and why the file cannot be read (it named the
    other file only). A model given on the command line that is a FIFO: said as such (it was
    "the file describes model 'rod_pendulum', not 'fifo.toml'")."""
    import os
    from wheeled_dyn.cli.main import main
    notes = tmp_path / "notes.toml"
    notes.write_text("these are my notes, not a model\n")
    path = _write(tmp_path, 'model = "rod_pendulum"', 'model = "notes.toml"')
    assert main(["compare", "rod_pendulum", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}:2: model: the model file it names cannot be read: {notes}" in err, err
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    assert main(["compare", str(fifo), str(_write(tmp_path))]) == 2
    err = capsys.readouterr().err
    assert str(fifo) in err and "FIFO" in err, err


def test_a_comparison_that_recurses_too_deeply_is_one_error(tmp_path, monkeypatch):
    r"""Python's compiler and SymPy recurse once per level of an expression: a comparison
    that runs out of stack (a probe's 1/(1 + P**16) did, in compiling) is one error naming
    the file, not a traceback. Made to run out here."""
    from wheeled_dyn.compare.steps import chain

    def deep(*args, **kwargs):
        raise RecursionError("maximum recursion depth exceeded")
    monkeypatch.setattr(chain, "with_steps", deep)
    path = _write(tmp_path)
    with pytest.raises(DerivationError) as err:
        ComparisonEngine(samples=20, param_sets=1).compare(load_derivation(path))
    _clear(err.value, path, "nested too deeply")


@pytest.mark.parametrize("use", ["(1 + {k}/1000)", "(1 + 0*{k})"])
@pytest.mark.parametrize("depth, refused", [(12, False), (16, True)])
def test_definitions_that_double_at_every_level(tmp_path, depth, refused, use):
    r"""``k = sin(j + theta) + cos(j - theta)``: two terms, each holding the one before, so a
    tree of 2**depth copies (a probe's 19 levels ran for minutes): counted written out —
    also where the element that names it multiplies it by 0 (the definition itself, written
    out to tell one derivation from another, hung a probe's comparison at 30 levels)."""
    defs = ['k0 = "theta"'] + [f'k{i} = "sin(k{i - 1} + theta) + cos(k{i - 1} - theta)"'
                               for i in range(1, depth + 1)]
    text = ROD.replace("[matrices]", "[definitions]\n" + "\n".join(defs) + "\n\n[matrices]"
                       ).replace("m*g*l/2*sin(theta)",
                                 "m*g*l/2*sin(theta)*" + use.format(k=f"k{depth}"))
    path = _write(tmp_path, text=text)
    if refused:
        with pytest.raises(DerivationError) as err:
            load_derivation(path)
        _clear(err.value, path, "nodes written out")
    else:
        assert load_derivation(path).equations


@pytest.mark.parametrize("configuration, agrees", [('psi = "theta"', True),
                                                   ('psi = "-theta"', False)])
def test_a_configuration_and_velocity_map_that_contradict_each_other(tmp_path, configuration,
                                                                     agrees):
    r"""A quasi set whose heading rate ``dtheta`` maps to the model's ``dpsi``: with
    ``psi = "theta"`` the two say the same; with ``psi = "-theta"`` the configuration makes
    dpsi = −dtheta — one clear error naming the velocity (the file agreed where the
    heading's angle enters no equation, whichever the document meant)."""
    text = ('title = "heading rate"\nmodel = "wip"\n[coordinates]\nkind = "quasi"\n'
            'positions = ["x", "theta"]\nvelocities = ["v", "dtheta"]\n'
            'accelerations = ["dv", "ddtheta"]\n'
            f'configuration = {{ x0 = "x", {configuration} }}\n'
            'velocity_map = { v = "cos(psi)*dx0 + sin(psi)*dy0", dtheta = "dpsi" }\n'
            '[matrices]\nequations = ["dv = 0", "ddtheta = 0"]\n')
    path = tmp_path / "heading.toml"
    path.write_text(text)
    if agrees:
        assert load_derivation(path).coordinates.velocity_map
        return
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    err = pickle.loads(pickle.dumps(info.value))
    assert err.item == "coordinates.velocity_map.dtheta" and "-dtheta" in str(err)
    assert "contradict" in str(err) and str(path) in str(err)
