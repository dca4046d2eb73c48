r"""The ROS balancer's Kane equations (``data/ros_balancer/ros_balancer_heading.toml``, every
element right) solved for their accelerations by Cramer's rule, as simulation code writes
them: the inertia as definitions M11 …, the right-hand side :math:`f = Bu - C\dot q - Q` as
f1 …, its determinant Det, and :math:`\ddot q = \operatorname{adj}(M) f / \det M`."""

from __future__ import annotations

import tomllib
from pathlib import Path

import sympy as sp

BALANCER = Path(__file__).parent / "data" / "ros_balancer"

#: The heading held (rows and columns x and θ): the document's coordinates, a planar one's.
PLANAR = """[coordinates]
kind = "quasi"
rolling = "eliminate"
positions = ["x", "theta"]
velocities = ["dx", "dtheta"]
units = { x = "m", theta = "rad" }
configuration = { x0 = "x", psi = "0", phi = "-theta" }
velocity_map = { dx = "cos(psi)*dx0 + sin(psi)*dy0", dtheta = "-dphi" }

[inputs]
tau_l = "u_l"
tau_r = "-u_r"

"""


def balancer_solved(folder: Path, old: str = "", new: str = "", heading: bool = False) -> Path:
    r"""The solved file written in ``folder``: in heading speed and pitch (the heading held),
    or with ``heading`` in all three of the file's coordinates (a 3×3 inverse: elements of
    thousands of characters once the definitions are written out); ``old`` written ``new``
    in M11."""
    text = (BALANCER / "ros_balancer_heading.toml").read_text()
    data = tomllib.loads(text)
    keep = [0, 1, 2] if heading else [0, 2]
    n = len(keep)
    A, C, B = (sp.Matrix(sp.sympify(" ".join(data["matrices"][k].split()))) for k in "ACB")
    Q = sp.Matrix(sp.sympify(data["matrices"]["Q"]))
    A, C, Q, B = A.extract(keep, keep), C.extract(keep, keep), Q.extract(keep, [0]), \
        B.extract(keep, [0, 1])
    velocities = sp.Matrix([sp.symbols("dx dpsi dtheta")[k] for k in keep])
    rhs = B * sp.Matrix(sp.symbols("u_l u_r")) - C * velocities - Q
    M = sp.Matrix(n, n, lambda i, j: sp.Symbol(f"M{i + 1}{j + 1}"))
    f = sp.Matrix([sp.Symbol(f"f{i + 1}") for i in range(n)])
    definitions = {f"M{i + 1}{j + 1}": sp.sstr(A[i, j]) for i in range(n) for j in range(n)}
    definitions.update({f"f{i + 1}": sp.sstr(rhs[i]) for i in range(n)})
    definitions["Det"] = sp.sstr(M.det())
    if old:
        assert definitions["M11"].count(old) == 1, definitions["M11"]
        definitions["M11"] = definitions["M11"].replace(old, new)
    solved = M.adjugate() * f
    head = text.split("[coordinates]")[0].replace(
        'model = "ros_balancer.toml"', f'model = "{BALANCER / "ros_balancer.toml"}"')
    coordinates = "[coordinates]" + text.split("[coordinates]")[1].split("[symbols]")[0] \
        if heading else PLANAR
    symbols = "[symbols]" + text.split("[symbols]")[1].split("[matrices]")[0]
    out = head + coordinates + symbols + "[definitions]\n" + "".join(
        f'{k} = "{v}"\n' for k, v in definitions.items())
    out += "\n[matrices]\nequations = [\n" + ",\n".join(
        f'  "dd{sp.sstr(v)[1:]} = ({sp.sstr(solved[i])})/Det"' for i, v in enumerate(velocities)
    ) + "\n]\n"
    path = folder / "solved.toml"
    path.write_text(out)
    return path
