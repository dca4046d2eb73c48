r"""Shipped derivation files copied under a test's folder, with places rewritten: planted
errors and right forms written otherwise start from the file as transcribed."""

from __future__ import annotations

from pathlib import Path

from wheeled_dyn.derivations.builtin import BUILTIN_DIR


def shipped(group: str, name: str) -> Path:
    r"""The shipped file ``name`` (with or without ``.toml``; step files too) of ``group``."""
    return BUILTIN_DIR / group / (name if name.endswith(".toml") else f"{name}.toml")


def rewritten_copy(source: Path, folder: Path, *replacements: tuple[str, str],
                   first: bool = False) -> Path:
    r"""``source`` written into ``folder`` under its own name with each ``(old, new)``
    replaced; each ``old`` occurs exactly once in the text it is applied to (with ``first``:
    at least once, and its first occurrence is replaced)."""
    text = source.read_text()
    for old, new in replacements:
        assert text.count(old) >= 1 if first else text.count(old) == 1, old
        text = text.replace(old, new, 1)
    path = folder / source.name
    path.write_text(text)
    return path
