r"""Model files: a model as data (TOML), read into the same
:class:`~.wheeled_model.ModelSpec` as a model written in Python. Format and a complete
example: ``docs/model-format.md``.

.. code-block:: toml

    name = "upkie_crouch"
    summary = "Upkie with its legs locked at a crouch: a two-wheeled pendulum"
    [urdf]
    package = "upkie-description"           # or: path = "robot.urdf" (relative to this file)
    [base]
    type = "planar"                         # planar (wheeled) | fixed | free
    body = "base"
    up = [0.0, 0.0, 1.0]
    [wheels]
    links = ["left_wheel_tire", "right_wheel_tire"]
    radius = 0.047
    [joints]
    locked = { left_hip = 0.6, left_knee = -1.2, right_hip = -0.6, right_knee = 1.2 }

Reading a file needs only :mod:`tomllib` (:func:`read_model_file`, used by ``wheeled-dyn list``
and by the derivation parser for the names of the declared coordinate sets);
:meth:`ModelFile.spec` resolves the URDF (a path, or a robot inside an installed description
package) and builds the spec. Every error names the file, the line and the key.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from ..paths import resolved
from ..derivations.source import SourceText, read_toml
from ..errors import InputFileError, OptionalDependencyError
from .urdf_packages import PACKAGES, resolve_package
from .urdf_values import MAX_MODEL_NUMBER, MAX_MODEL_TEXT

#: The bases a model may have (``[base] type``): a wheeled body on the ground, a fixed base, a
#: free-floating one (checked here, where reading a file needs no model).
BASES = ("planar", "fixed", "free")

if TYPE_CHECKING:
    from .wheeled_model import ModelSpec

#: Keys of a model file, by table (None: the top level).
KEYS: Mapping[str | None, tuple[str, ...]] = MappingProxyType({
    None: ("name", "summary", "description", "parameters", "default_coordinates", "urdf",
           "base", "wheels", "joints", "geometry", "draw", "contact", "rolling_wheel", "spring",
           "coordinates", "checks"),
    "urdf": ("path", "package", "package_dirs"),
    "base": ("type", "body", "up", "pitch", "forward"),
    "wheels": ("links", "radius", "inputs"),
    "joints": ("lock", "locked", "actuated", "inputs", "aliases"),
    "contact": ("link", "radius", "surface", "surface_radius", "centre", "vertex_radius",
                "polar_radius"),
    "rolling_wheel": ("link", "radius", "axis", "centre", "tyre_radius"),
    "spring": ("name", "joint", "stiffness", "rest"),
    "checks": ("accept_inertia",),
    "draw": ("fixed",),
})
#: Physical-parameter records a model file may name (``parameters = "wip"``).
PARAMETER_RECORDS: tuple[str, ...] = ("wip",)


@dataclass(frozen=True)
class ModelFile:
    r"""A model file that parsed: its path, name, summary and raw tables."""

    path: Path
    name: str
    summary: str
    data: Mapping[str, Any]
    source: SourceText

    @property
    def coordinate_sets(self) -> Mapping[str, Mapping[str, Any]]:
        r"""The declared coordinate sets, ``{name: raw table}`` (in the file's order)."""
        return MappingProxyType(dict(self.data.get("coordinates", {})))

    @property
    def parameters(self) -> str | None:
        return self.data.get("parameters")

    def fail(self, key: str, reason: str, table: str | None = None) -> InputFileError:
        line = self.source.line_of(table, key) if key else self.source.line_of(table)
        item = f"{table}.{key}" if table and key else (table or key)
        return InputFileError(self.path, f"{item}: {reason}", line=line)

    def urdf_path(self) -> tuple[Path, tuple[str, ...]]:
        r"""The URDF file and the package folders its ``package://`` meshes resolve in."""
        table = self.data["urdf"]
        dirs = tuple(str(resolved(self.path.parent / d)) for d in table.get("package_dirs", ()))
        package = table.get("package")
        if package is None:
            return resolved(self.path.parent / table["path"]), dirs
        try:
            urdf, pkg_dirs = resolve_package(package, table.get("path"))
        except OptionalDependencyError:
            raise
        except LookupError as exc:
            raise self.fail("package", str(exc), "urdf") from None
        return urdf, (*dirs, *pkg_dirs)

    def spec(self) -> "ModelSpec":
        r"""The :class:`~.wheeled_model.ModelSpec` this file describes (the URDF resolved)."""
        from .wheeled_model import ModelSpec
        from .contact import SphereContact
        from .rolling_wheel import WheelContact
        from .springs import JointSpring
        d = self.data
        urdf, package_dirs = self.urdf_path()
        base = d.get("base", {})
        wheels = d.get("wheels", {})
        joints = d.get("joints", {})
        locked = dict(joints.get("locked", {}))
        lock = (*joints.get("lock", ()), *(j for j in locked if j not in joints.get("lock", ())))
        inputs = wheels.get("inputs", joints.get("inputs"))
        if "inputs" in wheels and "inputs" in joints:    # the wheels' torques, then the joints'
            inputs = [*wheels["inputs"], *joints["inputs"]]
        contact = d.get("contact")
        return ModelSpec(
            name=self.name, urdf=urdf, body=base.get("body", ""),
            wheels=tuple(wheels.get("links", ())),
            up=_direction(base.get("up", (0.0, 0.0, 1.0))),
            pitch=bool(base.get("pitch", True)), lock=tuple(lock),
            forward=_direction(base["forward"]) if "forward" in base else None,
            locked=MappingProxyType({k: float(v) for k, v in locked.items()}),
            aliases=MappingProxyType(dict(joints.get("aliases", {}))),
            inputs=tuple(inputs) if inputs is not None else None,
            radius=float(wheels["radius"]) if "radius" in wheels else None,
            package_dirs=package_dirs, description=d.get("description", self.summary),
            base=base.get("type", "planar"), actuated=tuple(joints.get("actuated", ())),
            geometry=MappingProxyType({k: _geometry_value(v)
                                       for k, v in d.get("geometry", {}).items()}),
            fixed_geometry=tuple(d.get("draw", {}).get("fixed", ())),
            contact=SphereContact(**_arguments(contact)) if contact else None,
            rolling_wheels=tuple(WheelContact(**_arguments(w))
                                 for w in d.get("rolling_wheel", ())),
            springs=tuple(JointSpring(**w) for w in d.get("spring", ())),
            accept_inertia=tuple(d.get("checks", {}).get("accept_inertia", ())),
            coordinate_sets=self.coordinate_sets,
            default_coordinates=d.get("default_coordinates"), source=self.path)


def _direction(value: Any) -> tuple[float, float, float]:
    r"""A ``[base]`` direction as three floats (:func:`_validate` checked there are three)."""
    x, y, z = (float(v) for v in value)
    return x, y, z


def _arguments(table: Mapping[str, Any]) -> dict[str, Any]:
    r"""A table's entries as keyword arguments of a record: lists as tuples (the records are
    frozen; each checks its own values)."""
    return {k: tuple(v) if isinstance(v, list) else v for k, v in table.items()}


def _geometry_value(value: Any) -> Any:
    r"""A ``[geometry]`` value as the builder takes it (:mod:`.geometry`): a number as float,
    an expression, a list of expressions, ``{ value = x }``."""
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, list):
        return tuple(value)
    if isinstance(value, dict):
        return MappingProxyType({"value": float(value["value"])})
    return value


def _names(mf: ModelFile, table: str | None, key: str, value: Any) -> None:
    if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
        raise mf.fail(key, "expected a list of names", table)


def _finite(value: Any) -> bool:
    r"""Whether ``value`` is a number (not a boolean) of magnitude at most
    :data:`~.urdf_values.MAX_MODEL_NUMBER` (a radius of 1e300 makes every result NaN)."""
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value) and abs(value) <= MAX_MODEL_NUMBER)


def _numbers(mf: ModelFile, table: str | None, key: str, value: Any, n: int | None) -> None:
    ok = isinstance(value, list) and all(_finite(x) for x in value)
    if not ok or (n is not None and len(value) != n):
        raise mf.fail(key, f"expected {n or 'a list of'} finite numbers of magnitude at most "
                      f"{MAX_MODEL_TEXT}", table)


def _number(mf: ModelFile, table: str | None, key: str, value: Any) -> None:
    if not _finite(value):
        raise mf.fail(key, f"expected a finite number of magnitude at most "
                      f"{MAX_MODEL_TEXT}, got {value!r}", table)


def _check_table(mf: ModelFile, table: str, raw: Any, line_table: str | None = None) -> None:
    if not isinstance(raw, dict):
        raise mf.fail(table, "expected a table", None)
    for key in raw:
        if key not in KEYS[table]:
            raise mf.fail(key, "unknown key; valid: " + ", ".join(KEYS[table]),
                          line_table or table)


def _validate(mf: ModelFile) -> None:
    r"""Check every table of the file, in the order of ``docs/model-format.md``; the first
    error found is raised (:meth:`ModelFile.fail`: the file, line and key)."""
    d = mf.data
    _validate_top(mf, d)
    _validate_urdf(mf, d)
    for table in ("base", "wheels", "joints", "checks", "contact"):
        if table in d:
            _check_table(mf, table, d[table])
    _validate_base(mf, d.get("base", {}))
    _validate_joints(mf, d)
    _validate_geometry(mf, d.get("geometry", {}))
    if "draw" in d:
        _check_table(mf, "draw", d["draw"])
        if "fixed" in d["draw"]:
            _names(mf, "draw", "fixed", d["draw"]["fixed"])
    wheel_list = d.get("rolling_wheel", [])
    if not isinstance(wheel_list, list):
        raise mf.fail("rolling_wheel", "expected [[rolling_wheel]] tables")
    for w in wheel_list:
        _check_table(mf, "rolling_wheel", w)
    _validate_springs(mf, d.get("spring", []))
    sets = d.get("coordinates", {})
    if not isinstance(sets, dict) or not all(isinstance(v, dict) for v in sets.values()):
        raise mf.fail("coordinates", "expected [coordinates.<set name>] tables")
    if "parameters" in d and d["parameters"] not in PARAMETER_RECORDS:
        raise mf.fail("parameters", "expected one of " + ", ".join(PARAMETER_RECORDS))


def _validate_top(mf: ModelFile, d: Mapping[str, Any]) -> None:
    r"""The top level: known keys only, and its texts are strings."""
    for key in d:
        if key not in KEYS[None]:
            raise mf.fail(key, "unknown key or table; valid: " + ", ".join(KEYS[None]))
    for key in ("name", "summary", "description", "parameters", "default_coordinates"):
        if key in d and not isinstance(d[key], str):
            raise mf.fail(key, "expected a string")


def _validate_urdf(mf: ModelFile, d: Mapping[str, Any]) -> None:
    r"""``[urdf]``: a path or a package (strings), optional package folders."""
    if "urdf" not in d:
        raise mf.fail("urdf", "missing: give [urdf] path = \"...\" or package = \"...\"")
    _check_table(mf, "urdf", d["urdf"])
    urdf = d["urdf"]
    if "path" not in urdf and "package" not in urdf:
        raise mf.fail("urdf", "give path (relative to this file) or package (one of "
                      + ", ".join(PACKAGES) + ")")
    for key in ("path", "package"):
        if key in urdf and not isinstance(urdf[key], str):
            raise mf.fail(key, "expected a string", "urdf")
    if "package_dirs" in urdf:
        _names(mf, "urdf", "package_dirs", urdf["package_dirs"])


def _validate_base(mf: ModelFile, base: Mapping[str, Any]) -> None:
    r"""``[base]``: directions of three finite numbers not all zero, ``pitch`` a boolean,
    ``type`` and ``body`` strings."""
    for key in ("up", "forward"):
        if key in base:
            _numbers(mf, "base", key, base[key], 3)
            if not math.hypot(*base[key]) > 0:
                raise mf.fail(key, "expected a direction: three finite numbers, not all zero",
                              "base")
    if "pitch" in base and not isinstance(base["pitch"], bool):
        raise mf.fail("pitch", "expected true or false", "base")
    for key in ("type", "body"):
        if key in base and not isinstance(base[key], str):
            raise mf.fail(key, "expected a string", "base")
    if base.get("type", "planar") not in BASES:
        raise mf.fail("type", f"{base['type']!r}; expected one of {', '.join(BASES)}", "base")


def _validate_joints(mf: ModelFile, d: Mapping[str, Any]) -> None:
    r"""The lists of names of ``[wheels]``, ``[joints]`` and ``[checks]``, the wheel radius,
    and ``[joints]``' tables ``locked`` (joint = number) and ``aliases`` (joint = name)."""
    for table, key in (("wheels", "links"), ("wheels", "inputs"), ("joints", "lock"),
                       ("joints", "actuated"), ("joints", "inputs"),
                       ("checks", "accept_inertia")):
        if key in d.get(table, {}):
            _names(mf, table, key, d[table][key])
    wheels = d.get("wheels", {})
    if "radius" in wheels:
        _number(mf, "wheels", "radius", wheels["radius"])
        if not wheels["radius"] > 0:             # a starter's "radius = 0  # CHECK" left as is
            raise mf.fail("radius", f"expected the wheels' rolling radius, a positive number "
                          f"of metres, got {wheels['radius']!r}", "wheels")
    joints = d.get("joints", {})
    for key in ("locked", "aliases"):
        raw = joints.get(key, {})
        if not isinstance(raw, dict):
            raise mf.fail(key, "expected a table joint = value", "joints")
        for name, value in raw.items():
            if key == "locked":
                _number(mf, "joints", key, value)
            elif not isinstance(value, str) or not value.isidentifier():
                raise mf.fail(key, f"alias of {name!r}: expected a coordinate name", "joints")
        twice = [v for v in raw.values() if list(raw.values()).count(v) > 1]
        if key == "aliases" and twice:
            raise mf.fail(key, f"{twice[0]!r} names two joints", "joints")
    links = d.get("wheels", {}).get("links", [])
    again = [w for w in links if links.count(w) > 1]
    if again:
        raise mf.fail("links", f"{again[0]!r} is listed twice: give the left wheel's link, "
                      "then the right wheel's", "wheels")


def _validate_geometry(mf: ModelFile, geometry: Any) -> None:
    r"""``[geometry]``: a table of names, each entry as :func:`_geometry_entry` takes it."""
    if not isinstance(geometry, dict):
        raise mf.fail("geometry", "expected a table name = number")
    for name, value in geometry.items():
        if not name.isidentifier():
            raise mf.fail(name, "not a name", "geometry")
        _geometry_entry(mf, name, value)


def _geometry_entry(mf: ModelFile, name: str, value: Any) -> None:
    r"""A ``[geometry]`` entry: a number, an expression of the model's lengths, a list of
    them (equal lengths), or ``{ value = number }`` (docs/model-format.md)."""
    if isinstance(value, str) and value.strip():
        return
    if isinstance(value, list):
        if value and all(isinstance(v, str) and v.strip() for v in value):
            return
        raise mf.fail(name, "expected a list of lengths that are equal (\"2*origin_y(j)\", "
                      "...)", "geometry")
    if isinstance(value, dict):
        if set(value) != {"value"}:
            raise mf.fail(name, "expected { value = number } (a constant of its own)",
                          "geometry")
        _number(mf, "geometry", name, value["value"])
        return
    if not _finite(value):
        raise mf.fail(name, f"expected a number (magnitude at most {MAX_MODEL_TEXT}), a "
                      "length of the model (\"radius(wheel)\"), a list of equal lengths or "
                      f"{{ value = number }}; got {value!r}", "geometry")


def _validate_springs(mf: ModelFile, springs: Any) -> None:
    r"""``[[spring]]`` tables: a name, a joint (name or coordinate), a positive stiffness and
    a rest position (default 0)."""
    if not isinstance(springs, list):
        raise mf.fail("spring", "expected [[spring]] tables")
    for s in springs:
        _check_table(mf, "spring", s)
        for key in ("name", "joint"):
            if not isinstance(s.get(key), str) or not s[key].isidentifier():
                raise mf.fail(key if key in s else "spring", f"spring {key}: expected a name",
                              "spring" if key in s else None)
        if "stiffness" not in s:
            raise mf.fail("spring", f"spring {s['name']}: give its stiffness")
        _number(mf, "spring", "stiffness", s["stiffness"])
        if s["stiffness"] <= 0:
            raise mf.fail("stiffness", f"spring {s['name']}: expected a positive stiffness, "
                          f"got {s['stiffness']!r}", "spring")
        if "rest" in s:
            _number(mf, "spring", "rest", s["rest"])


def read_model_file(path: str | Path) -> ModelFile:
    r"""Read and check a model file (TOML only: no URDF, no Pinocchio). Errors:
    :class:`~wheeled_dyn.errors.InputFileError` with the file, line and key."""
    p = Path(path)
    if p.suffix.lower() == ".urdf" and p.is_file():
        from ..errors import InputFileError
        raise InputFileError(p, "a URDF is no model file: 'wheeled-dyn model "
                             f"{p} --out MODEL.toml' writes one (docs/model-format.md)")
    data, source = read_toml(p)
    mf = ModelFile(p, str(data.get("name", p.stem)), "", MappingProxyType(data), source)
    _validate(mf)
    summary = " ".join(str(data.get("summary", data.get("description", ""))).split())
    return ModelFile(p, mf.name, summary, mf.data, source)


def is_model_path(reference: str | Path) -> bool:
    r"""Whether a model reference is a file path (``.toml``, or containing a path separator)
    rather than a registered name."""
    text = str(reference)
    return text.endswith(".toml") or "/" in text or "\\" in text
