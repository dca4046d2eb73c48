r"""What a comparison is given, checked before anything is compared (by the engine, the
command line and the Python API alike): the size of its grid, and the names a derivation uses
of its model."""

from __future__ import annotations

from pathlib import Path

import numbers

from ...errors import ArgumentError, DerivationError, LimitError

#: Ranges of --samples and --param-sets, and of their product (the states of one comparison):
#: memory and time grow with it (at 10**9 states the comparison asked for 112 GiB).
MAX_SAMPLES, MAX_PARAM_SETS, MAX_STATES = 100_000, 1000, 1_000_000


def grid_size(samples: object, param_sets: object, seed: object,
              where: str = "ComparisonEngine") -> tuple[int, int, int]:
    r"""``(samples, param_sets, seed)`` checked: each an integer in its range
    (:data:`MAX_SAMPLES`, :data:`MAX_PARAM_SETS`), their product at most :data:`MAX_STATES`;
    :class:`ArgumentError` naming ``where`` for a value that is not an integer in range,
    :class:`LimitError` for too many states."""
    checked = []
    for name, value, low, high in (("samples", samples, 1, MAX_SAMPLES),
                                   ("param_sets", param_sets, 1, MAX_PARAM_SETS),
                                   ("seed", seed, 0, 2 ** 63 - 1)):
        if (isinstance(value, bool) or not isinstance(value, numbers.Integral)
                or not low <= int(value) <= high):
            raise ArgumentError(where, name, value, f"an integer from {low} to {high:,}")
        checked.append(int(value))
    if checked[0] * checked[1] > MAX_STATES:
        raise LimitError("samples × param_sets", checked[0] * checked[1],
                         f"at most {MAX_STATES:,} states", "memory and time grow with them")
    return checked[0], checked[1], checked[2]


def check_model_names(d) -> None:
    r"""The names derivation ``d`` uses of its model, checked before comparing: every key of
    ``[inputs]`` is a model input, every value of ``[symbols]`` uses the model's parameters
    and links. Raises :class:`~wheeled_dyn.derivations.errors.DerivationNameError` naming the
    file, the line, the item and the valid names."""
    from sympy.core.function import AppliedUndef

    from ...derivations.errors import DerivationNameError
    from ...derivations.expressions import GEOMETRY_NAMES
    from ...derivations.source import SourceText, read_small_text
    from ...models.registry import load_model, model_entry
    from .samples import namespace_values
    wm = load_model(d.model)
    entry = model_entry(d.model)
    values = namespace_values(wm, entry.parameters() if entry.parameters else None)
    src = SourceText(d.path, read_small_text(d.path) if d.path.is_file() else "")  # or Python
    for key in d.inputs:
        if key not in wm.input_names:
            raise DerivationNameError(d.path, f"inputs.{key}", "model input", key,
                                      wm.input_names, src.line_of("inputs", key))
    links = sorted({k[k.index("(") + 1:-1] for k in values if "(" in k})
    named: dict[str, set[str]] = {}      # the links, and the joints the geometry names
    for k in values:
        if "(" in k:
            named.setdefault(GEOMETRY_NAMES.get(k[:k.index("(")], "link"), set()).add(
                k[k.index("(") + 1:-1])
    for name, spec in d.symbols.items():
        if spec.value is None:
            continue
        item, line = f"symbols.{name}.value", src.line_of("symbols", name)
        args = set()
        for call in spec.value.atoms(AppliedUndef):
            link = str(call.args[0])
            args |= call.args[0].free_symbols
            key = f"{call.func.__name__}({link})"
            geometric = call.func.__name__ in GEOMETRY_NAMES
            if (link not in links or key not in values) and not geometric:
                from ...models.link_parameters import merged_links
                body = merged_links(wm).get(link)
                if body is not None:        # a link fixed to another: no parameters of its own
                    head = call.func.__name__ + "("
                    own = sorted({k[len(head):-1] for k in values if k.startswith(head)})
                    raise DerivationNameError(
                        d.path, item, f"link of its own (it is fixed to the rigid body named "
                        f"{body.carrier}: {', '.join(body.members)}; name that body)", link,
                        own, line)
            if link not in links and not geometric and _static(wm, link):
                raise DerivationNameError(
                    d.path, item, "moving link (it is fixed to the ground: no joint moves it, "
                    "its joints to the base being fixed or locked, so none of its parameters "
                    "enters the dynamics)", link, sorted(named.get("link", links)), line)
            if link not in links:
                kind = GEOMETRY_NAMES.get(call.func.__name__, "link")   # origin_x(joint)
                _axle_joint(d.path, item, line, wm, key if kind == "joint" else None)
                raise DerivationNameError(d.path, item, kind, link,
                                          sorted(named.get(kind, links)), line)
            if key not in values:
                raise DerivationNameError(d.path, item, "model parameter", key,
                                          [k for k in values if k.endswith(f"({link})")], line)
        for symbol in spec.value.free_symbols - args:
            if symbol.name not in values:
                raise DerivationNameError(d.path, item, "model parameter", symbol.name,
                                          [k for k in values if "(" not in k], line)


def _axle_joint(path, item: str, line: int | None, wm, key: str | None) -> None:
    r"""Raise :class:`~wheeled_dyn.errors.DerivationError` where ``key``
    (``origin_z(joint)``) names a planar model's URDF joint on the path from its root to its
    wheels: its origin is named by R and L, the rest kept as written, no length of its own
    to draw (:mod:`~wheeled_dyn.models.geometry`). Nothing for any other ``key``, or None."""
    from ...models.geometry import urdf_lengths
    if key is None or wm.base != "planar":
        return
    try:
        origins = urdf_lengths(Path(wm.spec.urdf).read_text())[0]
    except (OSError, ValueError):
        return
    joint = key[key.index("(") + 1:-1]
    if joint in origins:
        xyz = ", ".join(f"{v:g}" for v in origins[joint])
        raise DerivationError(path, item, f"{key}: joint {joint!r} joins the body to the "
                              "wheels, and the axle's height is R and half the track L, drawn "
                              "in every parameter set; the other components of its origin, "
                              f"({xyz}) as the URDF writes them, are kept in every set: write "
                              "them as numbers", line)


def _static(wm, link: str) -> bool:
    r"""Whether ``link`` is a link of the model's URDF that no joint moves (its body frame
    hangs from the world)."""
    import pinocchio as pin
    model = wm.model
    if not model.existFrame(link, pin.FrameType.BODY):
        return False
    return model.frames[model.getFrameId(link, pin.FrameType.BODY)].parentJoint == 0


__all__ = ["MAX_PARAM_SETS", "MAX_SAMPLES", "MAX_STATES", "check_model_names", "grid_size"]
