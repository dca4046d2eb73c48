"""Writes the notebooks of this folder (without outputs). Run: python notebooks/make_notebooks.py"""

from pathlib import Path

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

HERE = Path(__file__).resolve().parent

NOTEBOOKS = {
    "01_wip_from_urdf_to_report.ipynb": [
        new_markdown_cell("# The wheeled inverted pendulum, from URDF to report\n\n"
                          "Seed 001's pendulum is `urdf/wip.urdf`. We load it, look at its "
                          "equations in the document's coordinates (heading speed ẋ, heading "
                          "rate ψ̇, pitch rate φ̇), and compare the author's eq. (25) with them."),
        new_code_cell("import numpy as np\nimport wheeled_dyn as wd\n\n"
                      "wip = wd.load_model(\"wip\")\nprint(wip.coordinate_names, wip.geometry)\n"
                      "t = wd.matrices(wip, \"seed001\", phi=0.2, dx=1.0, dpsi=0.5, dphi=0.3)\n"
                      "np.set_printoptions(precision=4, suppress=True)\nprint(t.A); print(t.h); print(t.B)"),
        new_markdown_cell("The author's eq. (25), transcribed as printed, against the truth over "
                          "random states and random physically consistent parameters:"),
        new_code_cell("from wheeled_dyn.derivations import builtin_derivations, load_derivation\n"
                      "from wheeled_dyn.compare import ComparisonEngine\n"
                      "from wheeled_dyn.report import summary_lines\n\n"
                      "path = next(p for p in builtin_derivations() if p.name == \"eq25_lagrange.toml\")\n"
                      "result = ComparisonEngine(samples=200, param_sets=3).compare(load_derivation(path))\n"
                      "print(\"\\n\".join(summary_lines(result)))\n"
                      "for r in result.records:\n"
                      "    if r.verdict != \"agrees\":\n"
                      "        print(f\"{r.element:16} {r.verdict:10} {'; '.join(r.texts)}\")"),
        new_markdown_cell("The same as files: `wheeled-dyn compare wip <file> --out reports` "
                          "writes Markdown, an offline HTML page and JSON."),
    ],
    "02_why_the_heading_needs_the_reduction.ipynb": [
        new_markdown_cell("# Why the heading coordinate needs the rolling reduction\n\n"
                          "Seed 001 §4.3.5: Kim et al. have m_s d sin φ ψ̇² in the forward "
                          "equation; the author's Christoffel formula cannot produce it, because "
                          "none of his A's entries depends on x or ψ. The reason: ẋ (the heading "
                          "speed) is not the derivative of any coordinate. With q̇ = S(q)ν the "
                          "reduced equations have C_ν = SᵀCS + SᵀAṠ; the Christoffel formula "
                          "applied to ν as if they were coordinates misses SᵀAṠ."),
        new_code_cell("import numpy as np\nimport wheeled_dyn as wd\n\n"
                      "p = wd.WipParameters()\nwip = wd.load_model(\"wip\", p)\n"
                      "cmap = wd.CoordinateMap(wip, wd.builtin_coordinate_set(wip, \"seed001\"))\n"
                      "phi, dpsi = 0.3, 1.0\n"
                      "terms, S, v = cmap.reduce_at(cmap.model_configuration(np.array([0, 0, phi])),"
                      " np.array([0.0, dpsi, 0.0]))\n"
                      "print(\"h (true) with only the heading rate:\", terms.h)\n"
                      "print(\"m_S d sin(phi) dpsi**2 =\", p.m_S * p.d * np.sin(phi) * dpsi**2)"),
        new_markdown_cell("The Christoffel symbols of A(φ) alone, as the author computed them "
                          "(treating x, ψ, φ as coordinates), give no ψ̇² in row 1:"),
        new_code_cell("n = 3\nA = lambda ph: cmap.terms(np.array([0, 0, ph]), np.zeros(n)).A\n"
                      "eps = 1e-6\ndA = np.zeros((n, n, n))\n"
                      "dA[:, :, 2] = (A(phi + eps) - A(phi - eps)) / (2 * eps)   # only phi matters\n"
                      "c = 0.5 * (dA + dA.transpose(0, 2, 1) - dA.transpose(2, 0, 1))\n"
                      "nu = np.array([0.0, dpsi, 0.0])\n"
                      "print(\"Christoffel-as-if-coordinates h:\", np.einsum(\"ijk,j,k->i\", c, nu, nu))\n"
                      "print(\"missing S^T A Sdot nu:         \", terms.h - np.einsum(\"ijk,j,k->i\", c, nu, nu))"),
        new_markdown_cell("The missing term has a partner, −m_S d sin φ ẋψ̇ in the yaw equation, so "
                          "that gyroscopic forces do no work (νᵀh = ½νᵀȦν). Kim's equations have "
                          "the first and not the second: their model does not conserve energy."),
        new_code_cell("from wheeled_dyn.derivations import builtin_derivations, load_derivation\n"
                      "from wheeled_dyn.compare import ComparisonEngine\n"
                      "path = next(p for p in builtin_derivations() if p.name == \"kim_eq1_3.toml\")\n"
                      "result = ComparisonEngine(samples=200, param_sets=3).compare(load_derivation(path))\n"
                      "print(result.energy)\n"
                      "print([r.element for r in result.records if r.element.startswith(\"h[2]\") and r.verdict == \"differs\"])"),
    ],
    "03_benchmark_body_rod_pendulum.ipynb": [
        new_markdown_cell("# A benchmark body: the rod pendulum of seed 000, problem 4.4\n\n"
                          "A uniform rod of mass m and length l hinged at one end swings with "
                          "ω_n = √(3g/2l) for small angles. We linearise the true equations "
                          "(Pinocchio) about the hanging position and compare; then the "
                          "textbook's printed equation goes through the comparison engine."),
        new_code_cell("import numpy as np\nimport wheeled_dyn as wd\n"
                      "from wheeled_dyn.models.registry import model_parameters\n\n"
                      "rod = wd.load_model(\"rod_pendulum\")\n"
                      "p = model_parameters(rod)\n"
                      "m, l = p[\"M(rod)\"], 2 * -p[\"MZ(rod)\"] / p[\"M(rod)\"]   # first moment m l/2\n"
                      "cmap = wd.CoordinateMap(rod, wd.builtin_coordinate_set(rod, \"full\"))\n"
                      "eps = 1e-6\n"
                      "A = cmap.terms(np.zeros(1), np.zeros(1)).A[0, 0]\n"
                      "dQ = (cmap.terms(np.array([eps]), np.zeros(1)).Q[0]\n"
                      "      - cmap.terms(np.array([-eps]), np.zeros(1)).Q[0]) / (2 * eps)\n"
                      "print(\"omega_n from the truth:      \", np.sqrt(dQ / A))\n"
                      "print(\"sqrt(3 g / 2 l) (textbook):  \", np.sqrt(3 * p[\"g\"] / (2 * l)))"),
        new_code_cell("from wheeled_dyn.derivations import builtin_derivations, load_derivation\n"
                      "from wheeled_dyn.compare import ComparisonEngine\n"
                      "from wheeled_dyn.report import summary_lines\n"
                      "path = next(p for p in builtin_derivations(\"seed000\") if p.name == \"p4_4_rod_pendulum.toml\")\n"
                      "result = ComparisonEngine(samples=200, param_sets=3).compare(load_derivation(path))\n"
                      "print(\"\\n\".join(summary_lines(result)))"),
    ],
}


def main() -> None:
    for name, cells in NOTEBOOKS.items():
        nb = new_notebook(cells=cells, metadata={"kernelspec": {"name": "python3",
                                                                "display_name": "Python 3",
                                                                "language": "python"}})
        nbformat.write(nb, HERE / name)


if __name__ == "__main__":
    main()
