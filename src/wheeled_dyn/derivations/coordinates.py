r"""The ``[coordinates]`` table of a derivation file: the document's coordinates and how they
relate to the model's.

Either a built-in set of the model (``use = "seed001"``), or an inline set:

- ``kind = "holonomic"``: the model's coordinates are functions of the document's,
  :math:`q_{\text{model}} = f(q_{\text{doc}})` (``configuration``: model coordinate =
  expression of document positions and symbols); velocities are the time derivatives.
- ``kind = "quasi"``: some document velocities are not derivatives of coordinates (Kim's
  :math:`\dot x = \cos\psi\,\dot x_0 + \sin\psi\,\dot y_0`, the heading speed).
  ``velocity_map`` gives every document velocity as an expression linear in the model
  velocities, :math:`\nu = T(q)\,\dot q_{\text{model}}`; ``configuration`` gives the model
  coordinates that are functions of document positions (``psi = "psi"``, ``phi = "-theta"``).

``rolling`` says how the rolling constraints are treated: ``"eliminate"`` (reduced equations,
:math:`A_\nu = S^{\mathsf T} A S` ...), ``"multipliers"`` (full equations with
:math:`G^{\mathsf T}\lambda`) or ``"none"``. Names default to ``d<position>`` for velocities
and ``dd<position>`` for accelerations.

The parser knows the names of the sets a model file declares (``[coordinates.<name>]`` in
``data/models/<model>.toml``, or in the model file the derivation's ``model =`` names by path),
read with :mod:`tomllib` alone (it does not import the models: :func:`declared_sets`); a file
may ``use`` another set (one every model offers, e.g. ``heading``) if it also lists
``positions``. A ``model =`` path is relative to the derivation file
(:func:`resolve_model_reference`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import sympy

from ..paths import resolved
from ..errors import DerivationError, InputFileError
from .expressions import ExpressionError, parse_model_expression, parse_units, scan_names
from .limits import MAX_CONSTANT
from .schema import CoordinateSpec

KINDS: tuple[str, ...] = ("holonomic", "quasi")
ROLLING: tuple[str, ...] = ("eliminate", "multipliers", "none")
COORDINATE_KEYS: tuple[str, ...] = ("use", "kind", "positions", "velocities", "accelerations",
                                    "configuration", "velocity_map", "rolling", "units",
                                    "ranges")


@dataclass(frozen=True)
class BuiltinSet:
    r"""Names of a model's built-in coordinate set (the model defines the maps)."""

    positions: tuple[str, ...]
    velocities: tuple[str, ...]
    kind: str
    rolling: str
    units: Mapping[str, str] = field(default_factory=dict)


def _builtin_set(raw: Mapping[str, Any]) -> BuiltinSet:
    positions = tuple(raw.get("positions", ()))
    kind = raw.get("kind", "holonomic")
    return BuiltinSet(positions, tuple(raw.get("velocities", ["d" + p for p in positions])),
                      kind, raw.get("rolling", "eliminate" if kind == "quasi" else "none"),
                      MappingProxyType(dict(raw.get("units", {}))))


def declared_sets(model: str) -> Mapping[str, BuiltinSet]:
    r"""Names of the coordinate sets the model file of ``model`` (a shipped model's name or a
    model file path) declares; empty for a model written in Python or an unknown name."""
    from ..models.listing import shipped_model_files
    from ..models.model_file import is_model_path, read_model_file
    if is_model_path(model):
        mf = read_model_file(model)
    else:
        shipped = shipped_model_files().get(model)
        if shipped is None:
            return MappingProxyType({})
        mf = shipped
    return MappingProxyType({name: _builtin_set(raw)
                             for name, raw in mf.coordinate_sets.items()})


def resolve_model_reference(path: Path, model: str, line: int | None) -> str:
    r"""A derivation's ``model =``: a name unchanged, a model file path made absolute (relative
    to the derivation file ``path``); a path to no file raises :class:`DerivationError`."""
    from ..models.model_file import is_model_path
    if not is_model_path(model):
        return model
    target = resolved(path.parent / Path(model).expanduser())
    if not target.is_file():
        raise DerivationError(path, "model", f"no model file {model!r} (looked for {target})",
                              line)
    return str(target)


@dataclass(frozen=True)
class CoordinateNames:
    r"""The names part of ``[coordinates]``, read before any expression is parsed."""

    use: str | None
    kind: str
    positions: tuple[str, ...]
    velocities: tuple[str, ...]
    accelerations: tuple[str, ...]
    rolling: str
    units: Mapping[str, str]


def _names_list(path: Path, table: Mapping[str, Any], key: str, line: int | None,
                n: int | None) -> tuple[str, ...] | None:
    value = table.get(key)
    if value is None:
        return None
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise DerivationError(path, f"coordinates.{key}", "expected a list of names", line)
    for name in value:
        try:
            scanned = scan_names(name)
        except ExpressionError as exc:
            raise DerivationError(path, f"coordinates.{key}", exc.reason, line) from exc
        if len(scanned) != 1 or scanned[0][0] != name.strip():
            raise DerivationError(path, f"coordinates.{key}", f"{name!r} is not a name", line)
    if len(set(value)) != len(value):
        raise DerivationError(path, f"coordinates.{key}", "a name is listed twice", line)
    if n is not None and len(value) != n:
        raise DerivationError(path, f"coordinates.{key}",
                              f"{len(value)} names for {n} positions", line)
    return tuple(value)


def _choice(path: Path, table: Mapping[str, Any], key: str, allowed: tuple[str, ...],
            default: str, line: int | None) -> str:
    value = table.get(key, default)
    if value not in allowed:
        raise DerivationError(path, f"coordinates.{key}",
                              f"{value!r} is not one of {', '.join(allowed)}", line)
    return value


def _per_position(path: Path, table: Mapping[str, Any], key: str, what: str,
                  positions: tuple[str, ...], line_of: Callable[[str | None], int | None]):
    r"""The items of a ``[coordinates]`` sub-table keyed by position (``units``, ``ranges``);
    a non-table or a key that is not a position raises :class:`DerivationError`."""
    raw = table.get(key, {})
    if not isinstance(raw, dict):
        raise DerivationError(path, f"coordinates.{key}", f"expected a table name = {what}",
                              line_of(key))
    for name, value in raw.items():
        if name not in positions:
            raise DerivationError(path, f"coordinates.{key}.{name}", "not a position; "
                                  f"positions: {', '.join(positions)}", line_of(key))
        yield name, value


def _declared_set(path: Path, table: Mapping[str, Any], model: str, use: Any,
                  positions: tuple[str, ...] | None,
                  line_of: Callable[[str | None], int | None]) -> BuiltinSet | None:
    r"""The set ``use`` names among those the model file declares (None if it declares none
    of that name and the file lists the positions itself)."""
    if not isinstance(use, str):
        raise DerivationError(path, "coordinates.use", "expected a name", line_of("use"))
    try:
        sets = declared_sets(model)
    except InputFileError as exc:
        raise DerivationError(path, "model", f"model file: {exc}", None) from None
    builtin = sets.get(use)
    if builtin is None and positions is None:
        known = ", ".join(f"{model}:{name}" for name in sets) or "none"
        raise DerivationError(path, "coordinates.use", f"{use!r} is not a coordinate set "
                              f"declared by model {model!r}'s file (declared: {known}); "
                              "list its positions too", line_of("use"))
    for key in ("configuration", "velocity_map"):
        if key in table:
            raise DerivationError(path, f"coordinates.{key}", "not allowed with 'use' (the "
                                  "model defines the built-in set's maps)", line_of(key))
    if builtin is not None and positions is not None and positions != builtin.positions:
        raise DerivationError(path, "coordinates.positions", f"set {use!r} has positions "
                              f"{list(builtin.positions)}", line_of("positions"))
    return builtin


def _units(path: Path, table: Mapping[str, Any], builtin: BuiltinSet | None,
           positions: tuple[str, ...], line_of: Callable[[str | None], int | None]
           ) -> dict[str, str]:
    r"""The units of the positions (the built-in set's, then ``units``), each checked; and
    ``ranges``, each ``[low, high]`` with low < high."""
    units = dict(builtin.units) if builtin else {}
    for name, text in _per_position(path, table, "units", "units", positions, line_of):
        try:
            parse_units(str(text))
        except ExpressionError as exc:
            raise DerivationError(path, f"coordinates.units.{name}", exc.reason,
                                  line_of("units")) from exc
        units[name] = str(text)
    for name, pair in _per_position(path, table, "ranges", "[low, high]", positions, line_of):
        if (not isinstance(pair, list) or len(pair) != 2
                or not all(isinstance(x, (int, float)) and not isinstance(x, bool)
                           and math.isfinite(x) and abs(x) <= MAX_CONSTANT for x in pair)
                or not pair[0] < pair[1]):
            raise DerivationError(path, f"coordinates.ranges.{name}", "expected [low, high] "
                                  f"with low < high, finite numbers of magnitude at most "
                                  f"{MAX_CONSTANT:g}", line_of("ranges"))
    return units


def coordinate_names(path: Path, table: Any, model: str,
                     line_of: Callable[[str | None], int | None]) -> CoordinateNames:
    r"""Read the names of ``[coordinates]``; ``line_of(key)`` locates a key for messages."""
    if not isinstance(table, dict):
        raise DerivationError(path, "coordinates", "expected a table", line_of(None))
    for key in table:
        if key not in COORDINATE_KEYS:
            raise DerivationError(path, f"coordinates.{key}", "unknown key; valid: "
                                  + ", ".join(COORDINATE_KEYS), line_of(key))
    use = table.get("use")
    listed = _names_list(path, table, "positions", line_of("positions"), None)
    builtin: BuiltinSet | None = None
    if use is not None:
        builtin = _declared_set(path, table, model, use, listed, line_of)
    elif listed is None:
        raise DerivationError(path, "coordinates", "give 'use' (a built-in set) or 'positions'",
                              line_of(None))
    if listed:
        positions = listed
    elif builtin is not None:
        positions = builtin.positions
    else:
        raise DerivationError(path, "coordinates.positions", "expected at least one position",
                              line_of("positions"))
    n = len(positions)
    velocities = (_names_list(path, table, "velocities", line_of("velocities"), n)
                  or (builtin.velocities if builtin else tuple("d" + p for p in positions)))
    accelerations = (_names_list(path, table, "accelerations", line_of("accelerations"), n)
                     or tuple("dd" + p for p in positions))
    kind = _choice(path, table, "kind", KINDS, builtin.kind if builtin else "holonomic",
                   line_of("kind"))
    rolling = _choice(path, table, "rolling", ROLLING,
                      builtin.rolling if builtin else
                      ("eliminate" if kind == "quasi" else "none"), line_of("rolling"))
    for key, value in (("kind", kind), ("rolling", rolling)):
        if builtin is not None and value != getattr(builtin, key):
            raise DerivationError(path, f"coordinates.{key}", f"set {use!r} has {key} = "
                                  f"{getattr(builtin, key)!r} (the model's file defines the "
                                  "built-in set; the comparison reads it so)", line_of(key))
    if kind == "holonomic" and rolling == "eliminate":
        said = "'eliminate'" if "rolling" in table else f"'eliminate' (set {use!r})"
        raise DerivationError(path, "coordinates.rolling", f"{said}: eliminating rolling "
                              "constraints needs kind = \"quasi\"; for holonomic coordinates "
                              "write rolling = \"none\" (no rolling contact, or one the "
                              "coordinates already satisfy) or rolling = \"multipliers\"",
                              line_of("rolling") or line_of(None))
    units = _units(path, table, builtin, positions, line_of)
    all_names = [*positions, *velocities, *accelerations]
    if len(set(all_names)) != len(all_names):
        raise DerivationError(path, "coordinates", "positions, velocities and accelerations "
                              "must have distinct names", line_of(None))
    return CoordinateNames(use, kind, positions, velocities, accelerations, rolling,
                           MappingProxyType(units))


def _check_positions_used(path: Path, positions: tuple[str, ...],
                          configuration: Mapping[str, sympy.Expr], line: int | None) -> None:
    r"""Every position of a holonomic set enters the configuration map: a position no model
    coordinate depends on makes the map's Jacobian singular (``{ theta = "0" }``)."""
    used = {str(s) for e in configuration.values() for s in e.free_symbols}
    for name in positions:
        if name not in used:
            raise DerivationError(path, "coordinates.configuration", "no model coordinate "
                                  f"depends on the position {name!r}: the map does not "
                                  "determine it (its Jacobian is singular); give the model "
                                  f"coordinate {name!r} stands for as an expression of it",
                                  line)


def _plain(e: sympy.Expr) -> sympy.Expr:
    return e.xreplace({s: sympy.Symbol(s.name) for s in e.free_symbols})


def _check_rates(path: Path, names: CoordinateNames, configuration: Mapping[str, sympy.Expr],
                 velocity_map: Mapping[str, sympy.Expr], line: int | None) -> None:
    r"""In a quasi set, a document velocity named as a position's rate (``dtheta`` of
    ``theta``) whose map the configuration determines must be that rate: with
    ``psi = "-theta"`` the configuration makes :math:`\dot\psi = -\dot\theta`, and
    ``dtheta = "dpsi"`` says the opposite (a map whose terms the configuration does not fix,
    a model velocity it leaves free or a parameter, is not checked)."""
    rates = {p: sympy.Symbol(f"d{p}") for p in names.positions if f"d{p}" in names.velocities}
    model: dict[str, sympy.Expr] = {}
    for q, e in configuration.items():
        e = _plain(e)
        if all(s.name in rates for s in e.free_symbols):
            model[q] = e
            model[f"d{q}"] = sum((e.diff(s) * rates[s.name] for s in e.free_symbols),
                                 sympy.Integer(0))
    for p, rate in rates.items():
        if rate.name not in velocity_map:
            continue
        mapped = _plain(velocity_map[rate.name])
        speeds = [s for s in mapped.free_symbols if s.name[1:] in configuration]
        if not all(s.name in model for s in mapped.free_symbols) or any(
                mapped.diff(a, b) != 0 for a in speeds for b in speeds):
            continue                        # not linear in the velocities: said elsewhere
        given = mapped.xreplace({s: model[s.name] for s in mapped.free_symbols})
        if sympy.simplify(given - rate) != 0:
            raise DerivationError(path, f"coordinates.velocity_map.{rate.name}", (
                f"{rate.name} = {sympy.sstr(mapped)} is {sympy.sstr(sympy.simplify(given))} "
                f"by the configuration, not the rate of {p}: the configuration and the "
                "velocity map contradict each other (give the one the document means)"), line)


def _velocity_map(path: Path, names: CoordinateNames, raw: Mapping[str, str],
                  line: int | None) -> dict[str, sympy.Expr]:
    r"""``velocity_map``: every document velocity of a quasi set (none in another), each an
    expression in the model's names."""
    if names.kind == "quasi":
        missing = [v for v in names.velocities if v not in raw]
        if missing:
            raise DerivationError(path, "coordinates.velocity_map", "a quasi-velocity set "
                                  f"maps every document velocity; missing: {missing}", line)
    elif raw:
        raise DerivationError(path, "coordinates.velocity_map", "only for kind = \"quasi\"",
                              line)
    out: dict[str, sympy.Expr] = {}
    for doc_name, text in raw.items():
        item = f"coordinates.velocity_map.{doc_name}"
        if doc_name not in names.velocities:
            raise DerivationError(path, item, "not a document velocity; velocities: "
                                  + ", ".join(names.velocities), line)
        try:
            out[doc_name] = parse_model_expression(text)
        except ExpressionError as exc:
            raise DerivationError(path, item, exc.reason, line) from exc
    return out


def coordinate_spec(path: Path, table: Mapping[str, Any], names: CoordinateNames,
                    parse_doc: Callable[[str, str, str], sympy.Expr],
                    line_of: Callable[[str | None], int | None]) -> CoordinateSpec:
    r"""Parse the expressions of ``[coordinates]``. ``parse_doc(text, item, key)`` parses a
    document expression (raising the file's errors)."""
    configuration: dict[str, sympy.Expr] = {}
    velocity_map: dict[str, sympy.Expr] = {}
    if names.use is None:
        raw_conf = table.get("configuration", {})
        raw_vel = table.get("velocity_map", {})
        for key, raw in (("configuration", raw_conf), ("velocity_map", raw_vel)):
            if not isinstance(raw, dict) or not all(isinstance(v, str) for v in raw.values()):
                raise DerivationError(path, f"coordinates.{key}",
                                      "expected a table name = \"expression\"", line_of(key))
        if not raw_conf:
            raise DerivationError(path, "coordinates.configuration", "an inline set needs the "
                                  "model coordinates as expressions of the document's",
                                  line_of(None))
        for model_name, text in raw_conf.items():
            if not model_name.isidentifier():
                raise DerivationError(path, f"coordinates.configuration.{model_name}",
                                      "not a model coordinate name", line_of("configuration"))
            item = f"coordinates.configuration.{model_name}"
            configuration[model_name] = parse_doc(text, item, "configuration")
            if configuration[model_name].has(sympy.Abs, sympy.sign):
                raise DerivationError(path, item, "Abs and sign have no derivative where their "
                                      "argument is 0: a configuration map is differentiated "
                                      "(velocities, Coriolis terms); write the branch the "
                                      "document means", line_of("configuration"))
        if names.kind == "holonomic":
            _check_positions_used(path, names.positions, configuration,
                                  line_of("configuration"))
        velocity_map = _velocity_map(path, names, raw_vel, line_of("velocity_map"))
        if names.kind == "quasi":
            _check_rates(path, names, configuration, velocity_map, line_of("velocity_map"))
    return CoordinateSpec(names.use, names.kind, names.positions, names.velocities,
                          names.accelerations, MappingProxyType(configuration),
                          MappingProxyType(velocity_map), names.rolling, names.units,
                          MappingProxyType(dict(table)))
