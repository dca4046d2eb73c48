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


def own_wip_model(folder: Path, *urdf_replacements: tuple[str, str],
                  model_replacements: tuple[tuple[str, str], ...] = ()) -> tuple[Path, Path]:
    r"""The shipped ``wip`` model as a user's own: its model file (``wip.toml``, naming
    ``wip.urdf`` beside it) and a copy of its URDF, in ``folder``, each ``(old, new)``
    replaced once. Returns (model file, URDF)."""
    from wheeled_dyn.models.registry import MODELS
    from wheeled_dyn.paths import urdf_dir
    urdf = folder / "wip.urdf"
    text = (urdf_dir() / "wip.urdf").read_text()
    for old, new in urdf_replacements:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    urdf.write_text(text)
    model = Path(MODELS["wip"].source).read_text().replace('package = "wheeled-dyn"\n', "")
    for old, new in model_replacements:
        assert model.count(old) == 1, old
        model = model.replace(old, new)
    path = folder / "wip.toml"
    path.write_text(model.replace('name = "wip"', f'name = "{folder.name}_wip"'))
    return path, urdf


PUBLISHED = Path(__file__).parent / "data" / "published"


def published_copy(folder: Path, model: str, document: str, *replacements: tuple[str, str],
                   data: Path = PUBLISHED) -> Path:
    r"""A test model of ``data`` (``<model>.toml`` and its ``.urdf``) copied into ``folder``
    and its derivation ``<document>.toml`` written there as ``doc.toml`` with each
    ``(old, new)`` replaced (each occurring exactly once). Returns the derivation's path."""
    for name in (f"{model}.toml", f"{model}.urdf"):
        (folder / name).write_text((data / name).read_text())
    text = (data / f"{document}.toml").read_text()
    for old, new in replacements:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    path = folder / "doc.toml"
    path.write_text(text)
    return path
