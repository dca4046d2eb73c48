"""Writes the notebooks of this folder, executed, with their outputs (so that they read on
GitHub without running them). Run: .venv/bin/python notebooks/make_notebooks.py

tests/test_notebooks.py checks that the stored notebooks hold these cells, with outputs, and
executes them again (without errors)."""

from pathlib import Path

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

HERE = Path(__file__).resolve().parent
#: Seconds a cell may take.
CELL_TIMEOUT = 300

#: A derivation of a planar balancing robot, as a user writes it (docs/derivation-format.md):
#: examples/my_planar_robot.toml without its comment lines at the top.
MY_NOTES = "".join(line for line in (HERE.parent / "examples" / "my_planar_robot.toml")
                   .read_text(encoding="utf-8").splitlines(keepends=True)
                   if not line.startswith("#")).lstrip("\n")

NOTEBOOKS = {
    "01_wip_from_urdf_to_report.ipynb": [
        new_markdown_cell("# The wheeled inverted pendulum, from URDF to report\n\n"
                          "Seed 001's pendulum is `urdf/wip.urdf`. We load it, look at its "
                          "equations in the document's coordinates (heading speed ẋ, heading "
                          "rate ψ̇, pitch rate φ̇), and compare the author's eq. (25) with them."),
        new_code_cell("import numpy as np\nimport wheeled_dyn as wd\n\n"
                      "wip = wd.load_model(\"wip\")\nprint(wip.coordinate_names)\n"
                      "t = wd.matrices(wip, \"seed001\", phi=0.2, dx=1.0, dpsi=0.5, dphi=0.3)\n"
                      "np.set_printoptions(precision=4, suppress=True)\nprint(t.A); print(t.h); print(t.B)"),
        new_markdown_cell("The author's eq. (25), transcribed as printed, against the truth over "
                          "random states and random physically consistent parameters. A result "
                          "shows as its section of the HTML report: the causes first, then the "
                          "matrices, document | truth, then each element that differs."),
        new_code_cell("from wheeled_dyn.derivations import builtin_derivations, load_derivation\n"
                      "from wheeled_dyn.compare import ComparisonEngine\n\n"
                      "path = next(p for p in builtin_derivations() if p.name == \"eq25_lagrange.toml\")\n"
                      "result = ComparisonEngine(samples=200, param_sets=3).compare(load_derivation(path))\n"
                      "result"),
        new_markdown_cell("The same as files: `./wd compare wip <file> --out reports` "
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
    "03_your_own_derivation.ipynb": [
        new_markdown_cell(
            "# Your own derivation, checked and plotted\n\n"
            "You derived the equations of a planar balancing robot by hand: a body on two wheels, "
            "the distance rolled x and the pitch φ (φ > 0 tilts the body backward). The body is "
            "one of the project's models, `wip` (`./wd list` shows them all; for your own URDF, "
            "`./wd model robot.urdf --out robot.toml` writes a model file). The derivation is a "
            "TOML file, no code: your coordinates and how they map to the model's, your symbols "
            "and what they are in the model, your matrices as you wrote them "
            "(`docs/derivation-format.md`). Here it is written inline."),
        new_code_cell('MY_NOTES = """\\\n' + MY_NOTES + '"""'),
        new_code_cell("import tempfile\nfrom pathlib import Path\n\n"
                      "from wheeled_dyn.compare import ComparisonEngine\n"
                      "from wheeled_dyn.derivations import load_derivation\n\n"
                      "folder = Path(tempfile.mkdtemp())\n"
                      "mine = folder / \"my_planar_robot.toml\"\n"
                      "mine.write_text(MY_NOTES)\n"
                      "engine = ComparisonEngine(samples=200, param_sets=3)\n"
                      "result = engine.compare(load_derivation(mine))\n"
                      "result"),
        new_markdown_cell("Every element agrees, over random states and random physically "
                          "consistent parameters (the families under `[assumes]` are what the "
                          "derivation assumes: no products of inertia, the centre of mass on "
                          "the axis, no motor inertia). Now the same notes with one sign "
                          "slipped, in the centrifugal term of the first equation:"),
        new_code_cell("typo = folder / \"my_planar_robot_typo.toml\"\n"
                      "typo.write_text(MY_NOTES.replace(\"[[0, m_b*l*sin(phi)*dphi]\",\n"
                      "                                 \"[[0, -m_b*l*sin(phi)*dphi]\"))\n"
                      "result_typo = engine.compare(load_derivation(typo))\n"
                      "result_typo"),
        new_markdown_cell("The sign is found, and with it its consequence: the equations as "
                          "written do not conserve energy. Simulated from the same start "
                          "beside the truth (Pinocchio, rolling eliminated), zero input:"),
        new_code_cell("from IPython.display import Image\n"
                      "from wheeled_dyn.simulate.documented import side_by_side\n"
                      "from wheeled_dyn.simulate.plots import plot_side_by_side\n\n"
                      "run = side_by_side(load_derivation(typo), {\"phi\": 0.2, \"dx\": 0.5}, 3.0)\n"
                      "Image(plot_side_by_side(run))"),
        new_markdown_cell("From the command line: `./wd compare wip my_planar_robot.toml` "
                          "(reports in `reports/`), `./wd simulate my_planar_robot.toml` "
                          "(the same plot as a PNG file)."),
    ],
}


def build(name: str) -> nbformat.NotebookNode:
    r"""The notebook ``name`` without outputs (cell ids numbered: a new run changes no id)."""
    cells = [nbformat.from_dict(c) for c in NOTEBOOKS[name]]
    for k, cell in enumerate(cells):
        cell["id"] = f"cell-{k + 1}"
    return new_notebook(cells=cells, metadata={"kernelspec": {
        "name": "python3", "display_name": "Python 3", "language": "python"}})


def execute(nb: nbformat.NotebookNode) -> nbformat.NotebookNode:
    r"""Run ``nb`` in this folder (in place; no timings recorded, so the stored outputs change
    only when what they show does)."""
    import nbclient
    nbclient.NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                            record_timing=False,
                            resources={"metadata": {"path": str(HERE)}}).execute()
    return nb


def main() -> None:
    for name in NOTEBOOKS:
        nb = execute(build(name))
        nbformat.write(nb, HERE / name)
        print(f"wrote {name}")


if __name__ == "__main__":
    main()
