"""Expression limits, checked on the text before SymPy or NumPy sees it: size, nesting, power
bounds, constants, terms once multiplied out; errors name the file, the line and the item."""

from __future__ import annotations

import math
import os
import pickle

import pytest
import sympy as sp

from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.derivations.limits import MAX_DOCUMENT_TERMS
from wheeled_dyn.derivations.expressions import (MAX_EXPANDED_TERMS, MAX_EXPONENT,
                                                 MAX_NESTING, MAX_TOKENS, ExpressionError,
                                                 UndeclaredNameError, expanded_terms,
                                                 parse_expression, real_symbol)
from wheeled_dyn.errors import DerivationError, InputFileError

NAMES = {n: real_symbol(n) for n in ("x", "y", "th", "a", "b", "c", "d", "e")}
KIM = {p.name: p for p in builtin_derivations("seed001")}["kim_eq1_3.toml"]


@pytest.mark.parametrize("text,reason", [
    ("(1+sin(th))**(10**10**10)", "exponent 1e+10 out of range"),
    ("9**9**9**9", "exponent 3.8742e+08 out of range"),
    ("(1+sin(th))**2000", "exponent 2000 out of range"),
    ("x^100", "exponent 100 out of range"),
    ("x**th", "is not a constant number"),
    ("1e400*x", "number larger than"),
    ("10**60*10**60*x", "constant larger than"),
    ("+".join(["x"] * 20000), "expression too long"),
    ("(" * (MAX_NESTING + 1) + "x" + ")" * (MAX_NESTING + 1), "nested deeper"),
])
def test_limits(text, reason):
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, NAMES)
    assert reason in err.value.reason
    assert len(str(err.value)) < 400            # a long expression is shortened in the message


@pytest.mark.parametrize("text,expected", [
    ("x**2", "x**2"), ("x^2", "x**2"), ("x**(1/2)", "sqrt(x)"), ("x**-2", "x**(-2)"),
    (f"x**{MAX_EXPONENT}", f"x**{MAX_EXPONENT}"), ("2**10*x", "1024*x"),
    ("(1+sin(th))**4", "(sin(th) + 1)**4"), ("pi**2*x", "pi**2*x")])
def test_within_limits_unchanged(text, expected):
    assert str(parse_expression(text, NAMES)) == expected


def test_just_under_the_token_limit_parses():
    terms = (MAX_TOKENS - 1) // 2                 # x+x+...: 2 tokens per term
    assert parse_expression("+".join(["x"] * terms), NAMES) == terms * NAMES["x"]


@pytest.mark.parametrize("text", ["(a+b+c)**4", "(a+b)*(c+d+e)", "(a+b)**3*(c+d)**2 + x",
                                  "(a + b)/(c + d)", "sin(a+b)*(x+y)", "(a+b+c+d+e)**3"])
def test_expanded_terms_counts_what_expand_gives(text):
    r"""Without cancellations (distinct symbols) the count is exact: the same as SymPy's."""
    e = parse_expression(text, NAMES)
    assert expanded_terms(e) == len(sp.Add.make_args(sp.expand(e)))


def test_expanded_terms_bounds_cancellations_from_above():
    e = parse_expression("(a+b)**2 - (a-b)**2", NAMES)
    assert expanded_terms(e) == 6 >= len(sp.Add.make_args(sp.expand(e)))
    assert expanded_terms(parse_expression("(a+b+c+d+e)**16", NAMES)) == math.comb(20, 4)


def test_shipped_files_are_within_every_limit():
    from wheeled_dyn.derivations import builtin_groups
    for group in builtin_groups():
        for path in builtin_derivations(group):
            load_derivation(path)


def _mutated(tmp_path, old: str, new: str):
    text = KIM.read_text()
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, new, 1))
    line = next(i for i, t in enumerate(path.read_text().splitlines(), 1) if new[:12] in t)
    return path, line


@pytest.mark.parametrize("element,reason", [
    ("(m_c+m_s+sin(phi)+cos(phi)+d)**16*ddx", f"at most {MAX_DOCUMENT_TERMS}"),
    # multiplied out inside: a denominator, a function's argument (a probe's took 13 GB)
    ("ddx/(1 + (m_c+m_s+sin(phi)+cos(phi)+d+R+g)**64)", f"at most {MAX_DOCUMENT_TERMS}"),
    ("sin((m_c+m_s+cos(phi)+d+R+g)**40)*ddx", f"at most {MAX_DOCUMENT_TERMS}"),
    ("(1+sin(phi))**(10**10**10)*ddx", "exponent"), ("9**9**9**9*ddx", "exponent"),
    ("(" + "+".join(["m_c"] * 20000) + ")*ddx", "too long")])
def test_errors_name_file_line_and_item(element, reason, tmp_path):
    path, line = _mutated(tmp_path, "3*(m_c + m_s)*ddx", element)
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    assert (err.value.path, err.value.line, err.value.item) == (path, line, "equation 1")
    assert reason in str(err.value)


def test_an_equation_of_some_hundred_terms_is_read(tmp_path):
    r"""A three-coordinate robot's row replaced by a combination of its equations, with a full
    body inertia, has 186 terms once multiplied out (refused at 100): one of 182 is read; the
    limit refuses what would take minutes, not what a derivation writes."""
    element = "((m_c+m_s+sin(phi)+cos(phi)+d+R)**4 + (m_c+m_s+d+R+sin(psi)+cos(psi))**3)*ddx"
    assert 150 < expanded_terms(sp.sympify(element)) <= MAX_EXPANDED_TERMS
    path, _ = _mutated(tmp_path, "3*(m_c + m_s)*ddx", element)
    assert load_derivation(path).equations is not None

def test_definitions_are_counted_after_substitution(tmp_path):
    r"""A definition cannot smuggle a large expression past the limit."""
    text = KIM.read_text().replace(
        "[matrices]", '[definitions]\nS = "(m_c+m_s+sin(phi)+cos(phi)+d)**4"\n\n[matrices]', 1)
    text = text.replace("3*(m_c + m_s)*ddx", "S**4*ddx", 1)
    path = tmp_path / "doc.toml"
    path.write_text(text)
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    assert "equation 1" in str(err.value) and "terms once multiplied out" in str(err.value)


def test_powers_of_definitions_are_held_to_the_exponent_limit(tmp_path):
    r"""Definitions raised to powers in one another (``c1 = cos(phi - 1)**64``, ``c2 =
    c1**64`` ...) are a power of 64⁴ once substituted, which SymPy writes as one power and
    multiplying it out (the residual's text) took all the memory: refused, naming the
    equation, as a literal exponent beyond the limit is."""
    text = KIM.read_text().replace("[matrices]", "[definitions]\n" + "".join(
        f'c{k} = "{"cos(phi - 1)" if k == 1 else f"c{k - 1}"}**{MAX_EXPONENT}"\n'
        for k in range(1, 5)) + "\n[matrices]", 1)
    text = text.replace("3*(m_c + m_s)*ddx", "3*(m_c + m_s)*(1 + c4)*ddx", 1)
    path = tmp_path / "doc.toml"
    path.write_text(text)
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    assert "equation 1" in str(err.value), err.value
    assert f"exponent {MAX_EXPONENT ** 4} out of range" in str(err.value), err.value
    assert "definitions substituted" in str(err.value)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")
def test_fifo_folder_and_large_file(tmp_path):
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    with pytest.raises(InputFileError, match="is a FIFO"):
        load_derivation(fifo)
    with pytest.raises(InputFileError, match="is a folder"):
        load_derivation(tmp_path)
    big = tmp_path / "big.toml"
    with open(big, "wb") as fh:
        fh.truncate(5 * 1024 * 1024)
    with pytest.raises(InputFileError, match="at most"):
        load_derivation(big)


def test_internal_errors_pickle():
    for err in (ExpressionError("x**y", "bad"), UndeclaredNameError("x+q", "q", "link")):
        back = pickle.loads(pickle.dumps(err))
        assert type(back) is type(err) and str(back) == str(err)
        assert vars(back) == vars(err)


def test_symbol_values_are_held_to_the_expanded_limit(tmp_path):
    r"""A ``[symbols]`` value is substituted and solved for (the truth in the document's
    symbols): one whose expansion has about 9·10⁷ terms is refused when the file is read,
    naming its line, where it took minutes in the comparison before."""
    path, line = _mutated(tmp_path, 'value = "m_C"',
                          'value = "m_C + 1e-30*(m_C + m_S + d + R + I3 + Iw3 + g)**60"')
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    assert (err.value.line, err.value.item) == (line, "symbols.m_c.value")
    assert f"at most {MAX_EXPANDED_TERMS}" in str(err.value)


ROS = os.path.join(os.path.dirname(__file__), "data", "ros_balancer")


@pytest.mark.parametrize("expression,reason", [
    ("phi + 0*len(().__class__.__mro__)", "token '.' is not allowed"),
    ("phi + (x0 + y0 + psi + R)**40/10**30", f"at most {MAX_EXPANDED_TERMS}"),
    ("phi if x0 else psi", "Python keyword")])
def test_a_model_files_coordinate_sets_are_read_as_a_derivations_expressions(
        expression, reason, tmp_path):
    r"""A model file's ``[coordinates.<set>]`` is the user's text: it passes the same token
    scan and limits as a derivation's expressions before SymPy's parser (which evaluates
    Python) reads it, and the error names the model and the item."""
    import shutil

    from wheeled_dyn import builtin_coordinate_set, load_model
    from wheeled_dyn.errors import WheeledDynError
    shutil.copy(os.path.join(ROS, "ros_balancer.urdf"), tmp_path)
    text = open(os.path.join(ROS, "ros_balancer.toml")).read().replace(
        'name = "ros_balancer"', 'name = "ros_balancer_coords"')
    text += ('\n[coordinates.mine]\npositions = ["x0", "y0", "psi", "phi"]\n'
             f'configuration = {{ x0 = "x0", y0 = "y0", psi = "psi", phi = "{expression}" }}\n')
    (tmp_path / "robot.toml").write_text(text)
    wm = load_model(str(tmp_path / "robot.toml"))
    with pytest.raises(WheeledDynError) as err:
        builtin_coordinate_set(wm, "mine")
    assert reason in str(err.value) and "configuration.phi" in str(err.value)
    assert builtin_coordinate_set(wm, "heading").positions      # the others still read
