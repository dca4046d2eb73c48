r"""The examples of docs/derivation-format.md load and mean what the text says."""

from __future__ import annotations

import re
from pathlib import Path

import sympy

from wheeled_dyn.derivations import load_derivation

DOC = Path(__file__).resolve().parents[1] / "docs" / "derivation-format.md"


def _toml_blocks() -> list[str]:
    return re.findall(r"```toml\n(.*?)```", DOC.read_text(encoding="utf-8"), flags=re.S)


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
