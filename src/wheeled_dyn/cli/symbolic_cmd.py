r"""CLI: ``wheeled-dyn symbolic MODEL [--coords NAME] [--parameters MODE] [--latex | --json]``.

Prints the closed forms :math:`A, C, Q, B` (and, with ``--json``, :math:`h`) of a model in one
of its coordinate sets (:func:`~.wheeled.wheeled_symbolic`): for the WIP in seed 001's
physical names (``m_S, d, I1, ..., R, L, g, I_a``) by default, for other models in Khalil's
standard parameters of their links.
"""

from __future__ import annotations

import argparse
import json
from typing import TYPE_CHECKING

if TYPE_CHECKING:       # SymPy and Pinocchio load in the handler (a quick --help and list)
    import sympy as sp

#: Parameter modes (as :data:`~.wheeled.PARAMETER_MODES`, without importing SymPy for --help).
PARAMETER_MODES: tuple[str, ...] = ("physical", "numbers", "standard")


def _mode(model: str, requested: str | None) -> str:
    from ..models.registry import model_entry
    if requested:
        return requested
    return "physical" if model_entry(model).parameters is not None else "standard"


def _text(e: sp.Expr) -> str:
    import sympy as sp
    return sp.sstr(e)


def _matrix_lines(name: str, M: sp.Matrix) -> list[str]:
    lines = []
    for i in range(M.shape[0]):
        for j in range(M.shape[1]):
            label = f"{name}[{i + 1}]" if M.shape[1] == 1 and name in ("Q", "h") \
                else f"{name}[{i + 1},{j + 1}]"
            lines.append(f"  {label} = {_text(M[i, j])}")
    return lines


def _print_header(wm, cs, red, mode: str) -> None:
    r"""The model, its coordinates, positions, velocities, inputs and parameters (the text
    forms' first lines)."""
    print(f"model {wm.name}, coordinates {cs.name}: {cs.description}")
    print(f"positions {', '.join(map(str, red.q))}; velocities {', '.join(map(str, red.nu))}; "
          f"inputs {', '.join(wm.input_names)}")
    print(f"parameters ({mode}): {', '.join(map(str, red.parameters))}")
    _print_link_parameters(wm)


def _print_link_parameters(wm) -> None:
    r"""The link parameters a derivation file may name, both kinds with their reference points
    and the model's values (:func:`~wheeled_dyn.models.link_parameters.parameter_listing`)."""
    from ..models.link_parameters import parameter_listing
    print("link parameters a derivation may name (per rigid body, by the link carrying it):")
    print("\n".join(parameter_listing(wm)))


#: Models with more velocities than this get intermediate variables by default (``--form``).
EXPANDED_MAX_NV: int = 8


def _cmd_tree(args: argparse.Namespace, wm, cs, mode: str) -> int:
    r"""Closed forms with intermediate variables (:func:`~.tree_wheeled.tree_wheeled`)."""
    import re
    import time

    from ..symbolic.tree_code import operation_count
    from ..symbolic.tree_wheeled import tree_wheeled
    t0 = time.perf_counter()
    red = tree_wheeled(wm, cs, mode)
    seconds = time.perf_counter() - t0
    terms = {"A": red.A, "C": red.C, "Q": red.Q, "h": red.h}
    if red.B is not None:
        terms["B"] = red.B
    ops = operation_count(red.assignments)
    wanted = [e.strip() for e in re.split(r",(?![^\[]*\])", args.expand or "") if e.strip()]
    expanded = {}
    for label in wanted:
        expanded[label] = red.expand(_element(terms, label, args.model))
    if args.json:
        out = {"model": wm.name, "coordinate_set": cs.name, "parameters": mode,
               "form": "intermediate", "coordinates": [str(v) for v in red.nu],
               "positions": [str(q) for q in red.q], "inputs": list(wm.input_names),
               "seconds": seconds, "operations": ops.__dict__,
               "assignments": [[str(w), _text(e)] for w, e in red.assignments],
               "lengths": {n: {"value": v, "symbol": sym, "meaning": m}
                           for n, v, sym, m in _lengths(wm, mode, True)},
               **{k: [[_text(x) for x in row] for row in M.tolist()] for k, M in terms.items()},
               "expanded": {k: _text(v) for k, v in expanded.items()}}
        print(json.dumps(out, indent=2))
        return 0
    _print_header(wm, cs, red, mode)
    print(f"derived in {seconds:.2f} s with intermediate variables: {ops}")
    _print_lengths(wm, mode, True)
    print("A(q) nu' + C(q, nu) nu + Q(q) = B u, h = C nu; intermediate variables in order:")
    for w, e in red.assignments:
        print(f"  {w} = {_text(e)}")
    for name, M in terms.items():
        print(f"{name}:")
        print("\n".join(_matrix_lines(name, M)))
    for label, e in expanded.items():
        print(f"{label} expanded = {_text(e)}")
    return 0


def _lengths(wm, mode: str, tree: bool) -> list[tuple[str, float, str, str]]:
    r"""The model's named lengths and constants: (name, value, as the closed forms printed
    (``mode``, the tree's forms or not) write it, what it is)."""
    from ..symbolic.parameter_modes import drawn_symbols
    if wm.lengths is None:
        return []
    symbols = drawn_symbols(wm, mode, axle=tree)
    out = [(k, d.value, _text(symbols.get(k, "")), d.meaning + ("" if d.drawn else "; kept"))
           for k, d in wm.lengths.dimensions.items()]
    out += [(k, c.value, _text(symbols.get(k, "")), c.meaning + ("" if c.drawn else "; kept"))
            for k, c in wm.lengths.constants.items()]
    return out


def _print_lengths(wm, mode: str, tree: bool) -> None:
    rows = _lengths(wm, mode, tree)
    if not rows:
        return
    print("lengths (names a derivation's [symbols] may use; random parameter sets draw them):")
    for name, value, symbol, meaning in rows:
        print(f"  {name:32} {value:<10.6g} {symbol:16} {meaning}")


def _element(terms: dict, label: str, model: str):
    r"""``terms`` element named ``A[i,j]``, ``Q[i]`` ... (1-based)."""
    from ..errors import UnknownNameError
    import re
    m = re.fullmatch(r"([ACQhB])\[(\d+)(?:,(\d+))?\]", label)
    valid = [f"{k}[i,j]" if M.shape[1] > 1 else f"{k}[i]" for k, M in terms.items()]
    if not m or m.group(1) not in terms:
        raise UnknownNameError("element", label, valid, where=f"--expand of model {model}")
    M = terms[m.group(1)]
    i = int(m.group(2)) - 1
    j = int(m.group(3)) - 1 if m.group(3) else 0
    if not (0 <= i < M.shape[0] and 0 <= j < M.shape[1]):
        raise UnknownNameError("element", label, valid, where=f"--expand of model {model} "
                               f"({m.group(1)} is {M.shape[0]}x{M.shape[1]})")
    return M[i, j]


def _cmd_symbolic(args: argparse.Namespace) -> int:
    from ..coordinates import builtin_coordinate_set
    from ..models.registry import load_model
    from ..symbolic.printing import to_latex
    from ..symbolic.wheeled import derivation_joints, physical_latex, wheeled_symbolic
    wm = load_model(args.model)
    cs = builtin_coordinate_set(wm, args.coords)
    mode = _mode(args.model, args.parameters)
    derivation_joints(wm, mode)       # rounded right angles exact, as the comparisons' truth
    form = args.form
    if form == "auto":
        form = "intermediate" if wm.model.nv > EXPANDED_MAX_NV else "expanded"
    if form == "intermediate":
        return _cmd_tree(args, wm, cs, mode)
    red = wheeled_symbolic(wm, cs, mode)
    terms = {"A": red.A, "C": red.C, "Q": red.Q}
    if red.B is not None:
        terms["B"] = red.B
    if args.json:
        out = {"model": wm.name, "coordinate_set": cs.name, "parameters": mode,
               "coordinates": [str(v) for v in red.nu], "positions": [str(q) for q in red.q],
               "inputs": list(wm.input_names),
               "A": [[_text(x) for x in row] for row in red.A.tolist()],
               "C": [[_text(x) for x in row] for row in red.C.tolist()],
               "Q": [_text(x) for x in red.Q],
               "B": None if red.B is None else [[_text(x) for x in row]
                                                for row in red.B.tolist()],
               "h": [_text(x) for x in red.h],
               "lengths": {n: {"value": v, "symbol": sym, "meaning": m}
                           for n, v, sym, m in _lengths(wm, mode, False)}}
        if red.G is not None:
            out["G"] = [[_text(x) for x in row] for row in red.G.tolist()]
        print(json.dumps(out, indent=2))
        return 0
    dots = dict(zip(red.nu, red.q)) if len(red.nu) == len(red.q) else {}
    if args.latex:
        for name, M in terms.items():
            print(f"{name} = {to_latex(M, dots, physical_latex())}")
            print()
        return 0
    _print_header(wm, cs, red, mode)
    _print_lengths(wm, mode, False)
    print("A(q) nu' + C(q, nu) nu + Q(q) = B u")
    for name, M in terms.items():
        print(f"{name}:")
        print("\n".join(_matrix_lines(name, M)))
    return 0


def add_commands(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("symbolic", help="closed-form A, C, Q, B of a model in a coordinate set")
    p.add_argument("model", help="model name (see 'wheeled-dyn list') or model file (.toml)")
    p.add_argument("--coords", default=None, help="coordinate set (default: the model's)")
    p.add_argument("--parameters", default=None, choices=PARAMETER_MODES,
                   help="physical symbols (default for the WIP), the model's numbers, or "
                        "Khalil's standard parameters (default for other models)")
    p.add_argument("--form", default="auto", choices=("auto", "expanded", "intermediate"),
                   help="expanded sums, or intermediate variables (SYMORO-style, any size); "
                        f"auto: intermediate above {EXPANDED_MAX_NV} model velocities")
    p.add_argument("--expand", default=None, metavar="ELEMENTS",
                   help="with intermediate variables: also print these elements expanded, "
                        "e.g. A[1,1],Q[2]")
    out = p.add_mutually_exclusive_group()
    out.add_argument("--latex", action="store_true", help="print LaTeX")
    out.add_argument("--json", action="store_true",
                     help="print JSON (keys coordinates, A, C, Q, B, h as strings)")
    p.set_defaults(handler=_cmd_symbolic)
