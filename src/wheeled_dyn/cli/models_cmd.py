r"""CLI: ``wheeled-dyn list`` and ``wheeled-dyn matrices MODEL``."""

from __future__ import annotations

import argparse
import json
from typing import TYPE_CHECKING

from ..errors import ParameterError, StateError

if TYPE_CHECKING:       # NumPy, Pinocchio and the registry load in the handlers
    import numpy as np


def parse_assignments(text: str | None, what: str) -> dict[str, float]:
    r"""``"a=1,b=-0.5"`` → ``{"a": 1.0, "b": -0.5}``; a malformed item, a name given twice or
    a value that is not a decimal number (``1_0`` is not ten) of magnitude at most
    :data:`~wheeled_dyn.models.urdf_values.MAX_MODEL_NUMBER` raises :class:`StateError`
    naming it."""
    from ..models.urdf_values import MAX_MODEL_NUMBER, MAX_MODEL_TEXT, NUMBER
    # a --param entry is a parameter, not a state entry (its message said "state entry m_S")
    error = ParameterError if what == "--param" else StateError
    out: dict[str, float] = {}
    if not text:
        return out
    for item in text.split(","):
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise error(what, item, "name=value")
        key = key.strip()
        if key in out:
            raise error(key, value, f"one value: {key} is given twice in {what}")
        if not NUMBER.fullmatch(value.strip()):      # float() reads "1_0" as 10, "nan", "inf"
            raise error(key, value, "a decimal number")
        number = float(value)
        if number != number or number in (float("inf"), float("-inf")):
            raise error(key, value, "a finite number")
        if abs(number) > MAX_MODEL_NUMBER:
            raise error(key, value, f"a number of magnitude at most {MAX_MODEL_TEXT}")
        out[key] = number
    return out


def model_from_args(name: str, params_text: str | None):
    r"""The model with ``--param`` overrides applied (models with a parameter record only)."""
    from ..models.registry import load_model, model_entry
    changes = parse_assignments(params_text, "--param")
    if not changes:
        return load_model(name)
    entry = model_entry(name)
    if entry.parameters is None:
        raise ParameterError("--param", params_text, f"no parameters: model {name} is "
                                                     "defined by its URDF alone")
    return load_model(name, entry.parameters().replace(**changes))


#: Entries smaller than this fraction of a matrix's largest entry print as 0 (rounding noise).
PRINT_CHOP = 1e-12


def format_matrix(name: str, M: np.ndarray, rows: tuple[str, ...], cols: tuple[str, ...]) -> str:
    r"""A readable table of ``M`` with row and column names."""
    import numpy as np
    M = np.atleast_2d(np.asarray(M, dtype=float))
    scale = float(np.abs(M).max()) if M.size else 0.0
    M = np.where(np.abs(M) <= PRINT_CHOP * scale, 0.0, M)
    width = max([13, *(len(c) + 2 for c in cols)])
    label = max([8, *(len(r) for r in rows), len(name)])
    lines = [f"{name:>{label}} " + "".join(f"{c:>{width}}" for c in cols)]
    for r, row in zip(rows, M):
        lines.append(f"{r:>{label}} " + "".join(f"{x:>{width}.6g}" for x in row))
    return "\n".join(lines)


def _cmd_list(args: argparse.Namespace) -> int:
    from ..models.listing import model_summaries
    summaries = model_summaries()
    width = max(len(name) for name in summaries) + 1
    for name, summary in summaries.items():
        print(f"{name:{width}} {summary}")
    from ..models.listing import ADD_MODEL_HINT
    print("\n" + ADD_MODEL_HINT)
    return 0


def _cmd_model(args: argparse.Namespace) -> int:
    from ..errors import InputFileError
    from ..output import check_output_file
    from ..models.starter_file import write_starter
    if args.out is not None:
        out = check_output_file(args.out, ".toml")
        if out.exists() and not args.force:
            raise InputFileError(out, "exists; give --force to replace it")
    import sys

    from ..models.starter import inspect_urdf
    from ..models.starter_summary import summary
    accept = tuple(n.strip() for n in (args.accept_inertia or "").split(",") if n.strip())
    inventory = inspect_urdf(args.urdf, accept)
    lines, builds = summary(inventory)            # before writing: a failure leaves no file
    text = write_starter(args.urdf, args.out, inventory)
    if args.out is None:            # the file on stdout (to redirect), what was decided on stderr
        print(text, end="")
        print("\n".join(lines), file=sys.stderr)
    else:
        print("\n".join(lines))
        print(f"wrote {args.out}: " + ("check the lines marked CHECK, then run "
              f"'wheeled-dyn matrices {args.out}'" if builds else "it does not build yet "
              "(the reason above): edit it first (docs/model-format.md), then run "
              f"'wheeled-dyn matrices {args.out}'"))
    return 0


#: A's condition number above which :func:`_precision` notes that its smallest entries are
#: round-off (double precision keeps about 16 digits).
ILL_CONDITIONED = 1e10


def _precision(A) -> list[str]:
    r"""A note where A is so ill-conditioned that its smallest entries are round-off: numbers
    of very different sizes (``--param d=1e10`` printed A[dx,dpsi] = -21316 where 0 is
    exact, without a word) or a state where the coordinates are singular."""
    import numpy as np
    cond = float(np.linalg.cond(A))
    if cond <= ILL_CONDITIONED:
        return []
    return [f"A's condition number is {cond:.2g} (double precision keeps about 16 digits): "
            "its smallest entries may be round-off (numbers of very different sizes, or a "
            "state where the coordinates are singular)"]


def _cmd_matrices(args: argparse.Namespace) -> int:
    from ..constraints import CoordinateMap
    from ..coordinates import builtin_coordinate_set
    wm = model_from_args(args.model, args.param)
    cs = builtin_coordinate_set(wm, args.coords)
    cmap = CoordinateMap(wm, cs)
    q, nu = cmap.state_from(parse_assignments(args.state, "--state"))
    from ..api import finite_terms
    terms = finite_terms(cmap, q, nu)
    notes = [*wm.readings, *_precision(terms.A)]
    if args.json:
        out = {"model": wm.name, "coordinates": cs.name,
               "state": {**dict(zip(cs.positions, q.tolist())),
                         **dict(zip(cs.velocities, nu.tolist()))}, **terms.as_dict()}
        out["coordinates"] = list(cs.velocities)
        out["coordinate_set"] = cs.name
        out["notes"] = notes
        print(json.dumps(out, indent=2))
        return 0
    vel = cs.velocities
    from ..models.conventions import convention_table
    print("\n".join(convention_table(wm).lines()))
    print("".join(f"note: {r}\n" for r in notes), end="")
    print(f"model {wm.name}, coordinates {cs.name}: {cs.description}")
    print("state: " + ", ".join(f"{k}={v:g}" for k, v in zip((*cs.positions, *vel), (*q, *nu))))
    print(format_matrix("A", terms.A, vel, vel))
    print(format_matrix("C", terms.C, vel, vel))
    print(format_matrix("Q", terms.Q[:, None], vel, ("Q",)))
    if terms.B.shape[1]:
        print(format_matrix("B", terms.B, vel, terms.inputs))
    print(format_matrix("h=Cv", terms.h[:, None], vel, ("h",)))
    if terms.G is not None:
        print(format_matrix("G", terms.G, tuple(f"c{i}" for i in range(terms.G.shape[0])), vel))
    return 0


def add_commands(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("list", help="list the models")
    p.set_defaults(handler=_cmd_list)
    p = sub.add_parser("model", help="inspect a URDF and write a starting model file")
    p.add_argument("urdf", help="URDF file")
    p.add_argument("--out", default=None, help="model file to write (default: print it)")
    p.add_argument("--force", action="store_true", help="replace an existing --out file")
    p.add_argument("--accept-inertia", default=None, metavar="LINKS",
                   help="links whose inertia fails the URDF checks, accepted as written "
                        "(comma-separated; listed in the file's [checks] accept_inertia)")
    p.set_defaults(handler=_cmd_model)
    p = sub.add_parser("matrices", help="A, C, Q, B, h of a model in a coordinate set")
    p.add_argument("model", help="model name (see 'wheeled-dyn list') or model file (.toml)")
    p.add_argument("--coords", default=None, help="coordinate set (default: the model's)")
    p.add_argument("--state", default=None, help="state entries, e.g. phi=0.2,dpsi=1")
    p.add_argument("--param", default=None, help="physical parameters, e.g. m_S=50,d=0.4")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(handler=_cmd_matrices)
