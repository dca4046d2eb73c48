r"""Every kind of bad derivation file raises the project's error naming the file, the line, the
element and the symbol."""

from __future__ import annotations

import pytest
import sympy

from wheeled_dyn.derivations import DerivationNameError, builtin_derivations, load_derivation
from wheeled_dyn.errors import DerivationError, InputFileError, UnknownNameError

GOOD = """\
title = "two coordinates"
model = "wip"

[coordinates]
use = "seed001"

[symbols]
m = { value = "m_S", units = "kg" }
d = { value = "d", units = "m" }
g = { value = "g", units = "m/s**2" }

[matrices]
A = \"\"\"[
  [m, 0, -m*d*cos(phi)],
  [0, m*d**2, 0],
  [-m*d*cos(phi), 0, m*d**2]
]\"\"\"
Q = "[0, 0, -m*g*d*sin(phi)]"
"""


def _write(tmp_path, text, name="doc.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _line_of(text, fragment):
    return next(i for i, line in enumerate(text.splitlines(), start=1) if fragment in line)


def test_the_good_file_loads(tmp_path):
    d = load_derivation(_write(tmp_path, GOOD))
    assert d.A.shape == (3, 3) and d.Q.shape == (3, 1)


def test_missing_file():
    with pytest.raises(InputFileError, match="file not found"):
        load_derivation("/nonexistent/derivation.toml")


def test_malformed_toml_names_line_and_column(tmp_path):
    text = GOOD.replace('d = { value = "d", units = "m" }', 'd = { value = "d" units = "m" }')
    path = _write(tmp_path, text)
    with pytest.raises(InputFileError) as err:
        load_derivation(path)
    assert not isinstance(err.value, DerivationError)
    assert err.value.path == path
    assert err.value.line == _line_of(text, 'd = { value = "d" units')
    assert err.value.column is not None and err.value.column > 1
    assert f"{path}:{err.value.line}:{err.value.column}" in str(err.value)


def test_unknown_symbol_in_a_matrix_element(tmp_path):
    text = GOOD.replace("[0, m*d**2, 0]", "[0, m*d**2, mass*d]")
    path = _write(tmp_path, text)
    with pytest.raises(UnknownNameError) as err:
        load_derivation(path)
    e = err.value
    assert isinstance(e, DerivationNameError)
    assert e.name == "mass" and e.item == "A[2,3]" and e.path == path
    assert e.line == _line_of(text, "mass*d")
    assert "m" in e.valid and "phi" in e.valid and "dphi" in e.valid
    assert "A[2,3]" in str(e) and str(path) in str(e) and "'mass'" in str(e)


def test_unknown_symbol_in_an_equation(tmp_path):
    text = GOOD.split("[matrices]")[0] + """[matrices]
equations = [
  "m*ddx = 0",
  "m*d**2*ddpsi = 0",
  "m*d**2*ddphi - m*g*d*sin(phi) + k*dphi = 0",
]
"""
    with pytest.raises(DerivationNameError) as err:
        load_derivation(_write(tmp_path, text))
    assert err.value.name == "k" and err.value.item == "equation 3"
    assert err.value.line == _line_of(text, "k*dphi")


def test_unknown_link_or_parameter_when_the_model_names_are_given(tmp_path):
    path = _write(tmp_path, GOOD.replace('value = "m_S"', 'value = "M(bdy)"'))
    load_derivation(path)       # the parser alone does not know the model's links
    with pytest.raises(DerivationNameError) as err:
        load_derivation(path, links=["body", "wheel_left", "wheel_right"])
    assert err.value.name == "bdy" and err.value.kind == "link"
    assert err.value.item == "symbols.m.value"
    with pytest.raises(DerivationNameError) as err:
        load_derivation(path, parameters=["m_S", "g"], links=["bdy"])
    assert err.value.name == "d" and "m_S" in err.value.valid


@pytest.mark.parametrize("old, new, item, words", [
    ("[0, m*d**2, 0],", "[0, m*d**2],", "A[2,:]", "row 2 has 2 elements"),
    ('Q = "[0, 0, -m*g*d*sin(phi)]"', 'Q = "[0, -m*g*d*sin(phi)]"', "Q", "shape 2 entries"),
    ("[-m*d*cos(phi), 0, m*d**2]\n]", "[-m*d*cos(phi), 0, m*d**2],\n  [0, 0, 0]\n]", "A",
     "4 rows, expected 3×3"),
])
def test_wrong_shapes(tmp_path, old, new, item, words):
    text = GOOD.replace(old, new)
    assert text != GOOD
    with pytest.raises(DerivationError) as err:
        load_derivation(_write(tmp_path, text))
    assert err.value.item == item
    assert words in str(err.value)
    assert err.value.line is not None


def test_unparseable_element_names_it_and_its_line(tmp_path):
    text = GOOD.replace("[0, m*d**2, 0]", "[0, m*d**2 +, 0]")
    with pytest.raises(DerivationError) as err:
        load_derivation(_write(tmp_path, text))
    assert err.value.item == "A[2,2]"
    assert err.value.line == _line_of(text, "m*d**2 +")
    assert "A[2,2]" in str(err.value)


@pytest.mark.parametrize("element", ["__import__('os').system('true')", "m.real",
                                     "lambda: 1", "'text'", "m[0]"])
def test_code_is_not_an_expression(tmp_path, element):
    text = GOOD.replace("[0, m*d**2, 0]", f"[0, {element}, 0]")
    with pytest.raises(DerivationError) as err:
        load_derivation(_write(tmp_path, text))
    assert err.value.item in ("A[2,2]", "A")


def test_unknown_keys_and_tables(tmp_path):
    with pytest.raises(DerivationError, match="symbol: unknown key or table"):
        load_derivation(_write(tmp_path, GOOD.replace("[symbols]", "[symbol]")))
    with pytest.raises(DerivationError, match="valid: A, C, Q"):
        load_derivation(_write(tmp_path, GOOD.replace("Q = ", "Z = ")))
    with pytest.raises(DerivationError, match="symbols.m.unit"):
        load_derivation(_write(tmp_path, GOOD.replace('units = "kg"', 'unit = "kg"')))


def test_symbol_needs_a_value_or_a_role(tmp_path):
    with pytest.raises(DerivationError, match="exactly one of"):
        load_derivation(_write(tmp_path, GOOD.replace('m = { value = "m_S", ', 'm = { ')))
    with pytest.raises(DerivationError, match="already declared as a position"):
        load_derivation(_write(tmp_path, GOOD.replace('d = { value', 'phi = { value')))
    with pytest.raises(DerivationError, match="standard function"):
        load_derivation(_write(tmp_path, GOOD.replace('d = { value', 'sin = { value')))
    with pytest.raises(DerivationError, match="units"):
        load_derivation(_write(tmp_path, GOOD.replace('units = "kg"', 'units = "kilo"')))


def test_unknown_coordinate_set(tmp_path):
    with pytest.raises(DerivationError) as err:
        load_derivation(_write(tmp_path, GOOD.replace('use = "seed001"', 'use = "polar"')))
    assert err.value.item == "coordinates.use" and "wip:seed001" in str(err.value)


def test_inputs_must_be_mapped(tmp_path):
    text = GOOD.replace("[symbols]", "[symbols]\ntau = { input = true, units = \"N*m\" }")
    text = text.replace('Q = "[0, 0, -m*g*d*sin(phi)]"',
                        'Q = "[0, 0, -m*g*d*sin(phi)]"\nB = "[[1], [0], [1]]"')
    with pytest.raises(DerivationError, match="drives no model input"):
        load_derivation(_write(tmp_path, text))
    mapped = text.replace("[symbols]", "[inputs]\ntau_l = \"tau/2\"\ntau_r = \"tau/2\"\n\n"
                          "[symbols]")
    d = load_derivation(_write(tmp_path, mapped))
    assert d.B.shape == (3, 1) and d.input_symbols == (d.symbol("tau"),)


def test_definitions_expand_and_cycles_fail(tmp_path):
    text = GOOD.replace("[matrices]", "[definitions]\nJ = \"m*d**2\"\nK = \"2*J\"\n\n[matrices]")
    text = text.replace("[0, m*d**2, 0]", "[0, K/2, 0]")
    d = load_derivation(_write(tmp_path, text))
    assert d.A[1, 1] == d.symbol("m") * d.symbol("d") ** 2
    cyclic = text.replace('J = "m*d**2"', 'J = "K*m"')
    with pytest.raises(DerivationError, match="circular definition"):
        load_derivation(_write(tmp_path, cyclic))


def test_reconstructed_labels_must_exist(tmp_path):
    ok = GOOD + '\n[reconstructed]\n"A[3,3]" = "restored"\n'
    assert load_derivation(_write(tmp_path, ok)).reconstructed == {"A[3,3]": "restored"}
    with pytest.raises(DerivationError, match="outside A"):
        load_derivation(_write(tmp_path, ok.replace('"A[3,3]"', '"A[4,1]"')))
    with pytest.raises(DerivationError, match="no matrix C"):
        load_derivation(_write(tmp_path, ok.replace('"A[3,3]"', '"C[1,1]"')))


def test_missing_elements_are_recorded(tmp_path):
    d = load_derivation(_write(tmp_path, GOOD.replace("[0, m*d**2, 0]", "[0, ?, 0]")))
    assert d.missing == ("A[2,2]",)
    assert d.A[1, 1] is sympy.nan


def test_equations_need_one_equals_sign_and_n_rows(tmp_path):
    head = GOOD.split("[matrices]")[0] + "[matrices]\nequations = [\n"
    with pytest.raises(DerivationError, match="2 equations for 3 positions"):
        load_derivation(_write(tmp_path, head + '"m*ddx = 0", "m*ddpsi = 0"]\n'))
    with pytest.raises(DerivationError) as err:
        load_derivation(_write(tmp_path, head + '"m*ddx == 0", "m*ddpsi = 0", "ddphi = 0"]\n'))
    assert err.value.item == "equation 1"


def test_builtin_group_unknown():
    with pytest.raises(InputFileError, match="seed001"):
        builtin_derivations("nonexistent_group")


def test_coordinate_ranges_are_checked(tmp_path):
    r"""``[coordinates] ranges``: a name that is not a position, or a range with low >= high,
    is one error naming the key."""
    from wheeled_dyn.derivations import builtin_derivations, load_derivation
    from wheeled_dyn.errors import DerivationError
    src = next(p for p in builtin_derivations("seed002") if p.name == "s3_3_sphere_plane.toml")
    text = src.read_text()
    assert "ranges = { u = [0.2, 2.9416] }" in text
    for bad, where in (("ranges = { w = [0.2, 1.0] }", "coordinates.ranges.w"),
                       ("ranges = { u = [1.0, 0.2] }", "coordinates.ranges.u")):
        path = tmp_path / "bad.toml"
        path.write_text(text.replace("ranges = { u = [0.2, 2.9416] }", bad))
        with pytest.raises(DerivationError) as err:
            load_derivation(path)
        assert where in str(err.value)


@pytest.mark.parametrize("value", ['"eq25_lagrange"', "3", '["eq25_lagrange", 2]'])
def test_feeds_must_be_a_list_of_names(tmp_path, value):
    r"""A step file's ``feeds`` is a list of derivation names: a single string was read as its
    letters (the file then fed nothing), a number raised a raw TypeError."""
    from pathlib import Path
    shipped = next(p for p in builtin_derivations("seed001") if p.name == "eq25_lagrange.toml")
    steps = (Path(shipped).parent / "s4_energy_steps.toml").read_text()
    assert 'feeds = ["eq25_lagrange"]' in steps
    text = steps.replace('feeds = ["eq25_lagrange"]', f"feeds = {value}")
    with pytest.raises(DerivationError, match="feeds: expected a list") as caught:
        load_derivation(_write(tmp_path, text, "s4_copy_steps.toml"))
    assert caught.value.line == _line_of(text, "feeds =")


@pytest.mark.parametrize("key, value", [("kind", '"holonomic"'), ("rolling", '"multipliers"')])
def test_a_built_in_set_is_not_redeclared(tmp_path, key, value):
    r"""``[coordinates] use = "seed001"`` with another ``kind`` or ``rolling`` than the model's
    set: the file was loaded with its own, and compared with the model's."""
    shipped = next(p for p in builtin_derivations("seed001") if p.name == "kim_eq1_3.toml")
    text = shipped.read_text()
    assert 'use = "seed001"' in text
    text = text.replace('use = "seed001"', f'use = "seed001"\n{key} = {value}', 1)
    with pytest.raises(DerivationError, match=f"coordinates.{key}: set 'seed001' has {key}"):
        load_derivation(_write(tmp_path, text))


def test_an_unknown_uniform_link_is_named(tmp_path):
    r"""``[assumes] uniform`` names links of the model: another name is the file's error,
    naming the link and the model's links (read as the family ``uniform(link, ...)``)."""
    from pathlib import Path

    from wheeled_dyn.compare.grid.assumptions import declared
    source = Path(__file__).parent / "data" / "geometry" / "rod_pendulum_lengths.toml"
    text = source.read_text()
    assert 'uniform = ["rod"]' in text
    path = _write(tmp_path, text.replace('uniform = ["rod"]', 'uniform = ["nope"]'))
    with pytest.raises(DerivationError, match=r"assumes.uniform.*'nope'.*rod"):
        declared(load_derivation(path))


@pytest.mark.parametrize("name, read", [("ℓ", "l"), ("ﬁ", "fi"), ("ϑ", "θ")])
def test_a_name_python_reads_otherwise_is_one_error(tmp_path, name, read):
    r"""A symbol written ℓ (as physics texts print a length), ϑ, or the ligature ﬁ: Python
    reads each as another name in compiled code (NFKC), and the comparison ended in a
    ``NameError`` or ``SyntaxError`` traceback. One error names the file, the line and both
    spellings; it survives pickling, as every error of the project does."""
    import pickle
    text = GOOD.replace('d = { value = "d"', f'"{name}" = {{ value = "d"')
    path = _write(tmp_path, text)
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    message = str(info.value)
    assert f"{name!r} is read as {read!r}" in message and f":{_line_of(text, name)}:" in message
    assert str(pickle.loads(pickle.dumps(info.value))) == message


def test_a_file_of_too_many_symbols_is_one_error(tmp_path):
    r"""A file declaring more symbols than :data:`~wheeled_dyn.derivations.limits.MAX_SYMBOLS`
    (each value is parsed and checked: 20 000 took three minutes) is refused at once, naming
    the table and the limit."""
    from wheeled_dyn.derivations.limits import MAX_SYMBOLS
    extra = "".join(f'x{k} = {{ value = "d", units = "m" }}\n' for k in range(MAX_SYMBOLS))
    text = GOOD.replace('g = { value = "g", units = "m/s**2" }\n',
                        'g = { value = "g", units = "m/s**2" }\n' + extra)
    with pytest.raises(DerivationError, match=f"at most {MAX_SYMBOLS}") as info:
        load_derivation(_write(tmp_path, text))
    assert "symbols" in str(info.value)


@pytest.mark.parametrize("value, kind, valid, other", [
    ("CX(link9)", "link", "link1", "q2"), ("origin_x(knee)", "joint", "q2", "link2")])
def test_an_unknown_link_or_joint_lists_names_of_its_kind(tmp_path, value, kind, valid, other):
    r"""A probe's file for a two-link arm: ``CX(link9)`` listed the joints beside the links as
    valid, ``origin_x(knee)`` the links beside the joints."""
    from pathlib import Path

    from wheeled_dyn.compare.grid.inputs import check_model_names
    model = Path(__file__).parent / "data" / "published" / "two_link_arm.toml"
    text = (GOOD.replace('model = "wip"', f'model = "{model}"')
            .replace('use = "seed001"', 'positions = ["q1", "q2"]\n'
                     'configuration = { q1 = "q1", q2 = "q2" }')
            .replace('value = "d"', f'value = "{value}"')
            .replace('value = "m_S"', 'value = "M(link1)"'))
    text = text[:text.index("[matrices]")] + '[matrices]\nA = "[[m, 0], [0, m]]"\n'
    d = load_derivation(_write(tmp_path, text))
    with pytest.raises(DerivationNameError) as err:
        check_model_names(d)
    assert err.value.kind == kind
    assert valid in err.value.valid and other not in err.value.valid
