r"""The examples of docs/derivation-format.md and its pages (derivation-latex.md,
derivation-steps.md) load and mean what the text says."""

from __future__ import annotations

import re
from pathlib import Path

import sympy

from wheeled_dyn.derivations import load_derivation

DOCS = Path(__file__).resolve().parents[1] / "docs"
#: The format's pages: the main page (its complete example first), LaTeX input, steps.
PAGES = ("derivation-format.md", "derivation-latex.md", "derivation-steps.md")


def _toml_blocks() -> list[str]:
    text = "".join((DOCS / page).read_text(encoding="utf-8") for page in PAGES)
    return re.findall(r"```toml\n(.*?)```", text, flags=re.S)


def test_the_complete_example_loads_in_both_forms(tmp_path):
    blocks = _toml_blocks()
    full, equations = blocks[0], blocks[1]
    matrix_file = tmp_path / "example.toml"
    matrix_file.write_text(full, encoding="utf-8")
    mat = load_derivation(matrix_file)
    eq_file = tmp_path / "example_eq.toml"
    eq_file.write_text(full.split("[matrices]")[0] + equations, encoding="utf-8")
    eqs = load_derivation(eq_file)
    A, h, Q, B, _ = eqs.read_off()
    assert sympy.simplify(A - mat.A) == sympy.zeros(2, 2)
    assert sympy.simplify(mat.C * sympy.Matrix(mat.velocities) - h) == sympy.zeros(2, 1)
    assert Q == mat.Q and B == mat.B
    assert mat.coordinates.configuration["hinge"] == -mat.symbol("th")


def test_the_steps_example_is_judged_right(tmp_path):
    r"""The complete steps-only example (energies, a first integral, linearised equations and
    stated results) loads and every record agrees with its model; a planted frequency off by
    √2 differs."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    (block,) = [b for b in _toml_blocks() if 'kind = "critical speed"' in b]
    for text, planted in ((block, False),
                          (block.replace('value = "sqrt(3*g/(2*L))"', 'value = "sqrt(3*g/L)"', 1),
                           True)):
        path = tmp_path / "steps_example.toml"
        path.write_text(text, encoding="utf-8")
        result = ComparisonEngine(samples=20, param_sets=1, seed=1).compare(load_derivation(path))
        verdicts = {r.element: r.verdict for r in result.records if r.key == "step"}
        assert len(verdicts) == 7
        wrong = {e for e, v in verdicts.items() if v != "agrees"}
        assert wrong == ({"(e) frequency value"} if planted else set()), verdicts


def test_the_newton_euler_example_is_judged_right(tmp_path):
    r"""The documented balance example agrees; its moment equation with one arm's sign flipped
    names that force."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    (block,) = [b for b in _toml_blocks() if 'kind = "newton-euler"' in b]
    flipped = block.replace("-F_x*a*cos(theta) - F_y", "-F_x*a*cos(theta) + F_y", 1)
    for text, wrong in ((block, set()), (flipped, {"(1)-(3) newton-euler (3)"})):
        path = tmp_path / "balance.toml"
        path.write_text(text, encoding="utf-8")
        result = ComparisonEngine(samples=20, param_sets=1, seed=1).compare(load_derivation(path))
        records = {r.element: r for r in result.records if r.key == "step"}
        assert len(records) == 3
        assert {e for e, r in records.items() if r.verdict != "agrees"} == wrong
        if wrong:
            assert any("term F_y: sign" in x for x in records[next(iter(wrong))].texts)


def test_steps_accept_latex(tmp_path):
    r"""A step's value, components or relations pasted as LaTeX (``{ latex = '...' }``, or a
    list) read as the same expressions as the SymPy text, and are judged the same."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    (block,) = [b for b in _toml_blocks() if 'kind = "critical speed"' in b]
    plain = 'value = "I*dphi**2/2 + m*L**2/6*(dtheta**2 + dphi**2*sin(theta)**2)"'
    relations = 'relations = ["m*L**2/3*ddtheta = -(m*g*L/2 - m*L**2*W**2/3)*theta", "ddphi = 0"]'
    assert plain in block and relations in block
    latex = block.replace(plain, r"value = { latex = '\frac{1}{2} I \dot{\phi}^2 + \frac{m L^2}{6}"
                                 r"\left(\dot{\theta}^2 + \dot{\phi}^2 \sin^2\theta\right)' }")
    latex = latex.replace(relations, r"relations = { latex = ['\frac{m L^2}{3}\ddot{\theta} = "
                                     r"-\left(\frac{m g L}{2} - \frac{m L^2 W^2}{3}\right)\theta', "
                                     r"'\ddot{\phi} = 0'] }")
    paths = []
    for name, text in (("plain.toml", block), ("latex.toml", latex)):
        paths.append(tmp_path / name)
        paths[-1].write_text(text, encoding="utf-8")
    a, b = (load_derivation(p) for p in paths)
    for s, t in zip(a.steps, b.steps):
        assert all(sympy.simplify(x - y) == 0 for x, y in zip(s.components, t.components))
    assert b.steps[0].printed[0].startswith(r"\frac{1}{2}")
    result = ComparisonEngine(samples=20, param_sets=1, seed=1).compare(b)
    assert all(r.verdict == "agrees" for r in result.records if r.key == "step")


def test_the_lengths_example_is_the_tested_file_and_finds_a_length_error(tmp_path):
    r"""The lengths example is the rod pendulum file of the tests (its [source] left out) and
    is judged right; with l**2 written for l in Q, Q[1] differs with the power named."""
    from wheeled_dyn.compare.engine import ComparisonEngine
    (block,) = [b for b in _toml_blocks() if 'value = "length(rod)"' in b]
    tested = Path(__file__).parent / "data" / "geometry" / "rod_pendulum_lengths.toml"
    assert load_derivation(_written(tmp_path, block)).read_off() == \
        load_derivation(tested).read_off()
    for text, wrong in ((block, None), (block.replace("m*g*l/2*sin", "m*g*l**2/2*sin"), "Q[1]")):
        result = ComparisonEngine(samples=50, param_sets=3, seed=1).compare(
            load_derivation(_written(tmp_path, text)))
        bad = {r.element: r for r in result.records if r.verdict != "agrees"}
        assert set(bad) == ({wrong} if wrong else set()), bad
        if wrong:
            assert any(d.startswith("power: l**2 where l fits") for d in bad[wrong].texts)


def _written(folder: Path, text: str) -> Path:
    path = folder / "lengths_example.toml"
    path.write_text(text, encoding="utf-8")
    return path
