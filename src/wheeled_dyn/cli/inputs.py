r"""What the ``compare``, ``report`` and ``simulate`` commands are given, checked before
anything is compared: the grid's size, the derivation files named (a folder stands for its
files), and the names a derivation uses of its model."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path


#: Defaults of the default report: states per parameter set, parameter sets.
DEFAULT_SAMPLES, DEFAULT_PARAM_SETS = 1000, 5
#: Ranges of --samples and --param-sets, and of their product (the states of one comparison):
#: memory and time grow with it (at 10**9 states the comparison asked for 112 GiB).
MAX_SAMPLES, MAX_PARAM_SETS, MAX_STATES = 100_000, 1000, 1_000_000


def check_grid(samples: int, param_sets: int) -> None:
    r"""Raise :class:`~wheeled_dyn.errors.LimitError` unless ``1 <= samples <= MAX_SAMPLES``,
    ``1 <= param_sets <= MAX_PARAM_SETS`` and their product is at most ``MAX_STATES``."""
    from ..errors import LimitError
    if not 1 <= samples <= MAX_SAMPLES:
        raise LimitError("--samples", samples, f"an integer from 1 to {MAX_SAMPLES}")
    if not 1 <= param_sets <= MAX_PARAM_SETS:
        raise LimitError("--param-sets", param_sets, f"an integer from 1 to {MAX_PARAM_SETS}")
    if samples * param_sets > MAX_STATES:
        raise LimitError("--samples × --param-sets", samples * param_sets,
                         f"at most {MAX_STATES:,} states", "memory and time grow with them")


def input_files(entries: Sequence[str | Path]) -> list[Path]:
    r"""The derivation files named on the command line (a folder stands for its ``*.toml``
    files); a folder without any raises :class:`~wheeled_dyn.errors.InputFileError`."""
    from ..derivations.builtin import derivation_files
    from ..errors import InputFileError
    files: list[Path] = []
    for entry in entries:
        found = derivation_files([entry])
        if not found:
            raise InputFileError(entry, "folder without derivation files (*.toml)")
        files.extend(found)
    return files


def check_model_names(d) -> None:
    r"""The names derivation ``d`` uses of its model, checked before comparing: every key of
    ``[inputs]`` is a model input, every value of ``[symbols]`` uses the model's parameters
    and links. Raises :class:`~wheeled_dyn.derivations.errors.DerivationNameError` naming the
    file, the line, the item and the valid names."""
    from sympy.core.function import AppliedUndef

    from ..derivations.errors import DerivationNameError
    from ..derivations.expressions import GEOMETRY_NAMES
    from ..derivations.source import SourceText, read_small_text
    from ..models.registry import load_model, model_entry
    from ..compare.grid.samples import namespace_values
    wm = load_model(d.model)
    entry = model_entry(d.model)
    values = namespace_values(wm, entry.parameters() if entry.parameters else None)
    src = SourceText(d.path, read_small_text(d.path) if d.path.is_file() else "")  # or Python
    for key in d.inputs:
        if key not in wm.input_names:
            raise DerivationNameError(d.path, f"inputs.{key}", "model input", key,
                                      wm.input_names, src.line_of("inputs", key))
    links = sorted({k[k.index("(") + 1:-1] for k in values if "(" in k})
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
                from ..models.link_parameters import merged_links
                body = merged_links(wm).get(link)
                if body is not None:        # a link fixed to another: no parameters of its own
                    raise DerivationNameError(
                        d.path, item, f"link of its own (it is fixed to the rigid body named "
                        f"{body.carrier}: {', '.join(body.members)}; name that body)", link,
                        links, line)
            if link not in links:
                kind = GEOMETRY_NAMES.get(call.func.__name__, "link")   # origin_x(joint)
                raise DerivationNameError(d.path, item, kind, link, links, line)
            if key not in values:
                raise DerivationNameError(d.path, item, "model parameter", key,
                                          [k for k in values if k.endswith(f"({link})")], line)
        for symbol in spec.value.free_symbols - args:
            if symbol.name not in values:
                raise DerivationNameError(d.path, item, "model parameter", symbol.name,
                                          [k for k in values if "(" not in k], line)
