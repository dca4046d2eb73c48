r"""Robots inside installed description packages, named by a model file's ``[urdf] package``.

=================== ============================================ ==============================
package             ``path`` is relative to                      without ``path``
=================== ============================================ ==============================
wheeled-dyn         the toolkit's shipped URDFs (``urdf/``)      (path required)
example-robot-data  ``<site-packages>/cmeel.prefix/share/        (path required)
                    example-robot-data/`` (e.g. ``robots/
                    tiago_description/robots/tiago.urdf``)
upkie-description   the ``upkie_description`` package folder     ``upkie_description.URDF_PATH``
=================== ============================================ ==============================

Each also gives the folders ``package://`` mesh names resolve in. A package that is not
installed raises :class:`~wheeled_dyn.errors.OptionalDependencyError` with the command that
installs it; a path that is not in the package raises :class:`LookupError` (reported by the
model file with its line).
"""

from __future__ import annotations

from pathlib import Path

from ..errors import OptionalDependencyError
from ..paths import example_robot_data_share, urdf_dir, resolved

#: Package names a model file may give.
PACKAGES: tuple[str, ...] = ("wheeled-dyn", "example-robot-data", "upkie-description")


def _inside(root: Path, path: str | None, package: str) -> Path:
    if path is None:
        raise LookupError(f"package {package!r} needs path = \"...\" (relative to {root})")
    found = resolved(root / path)
    if not found.is_file():
        raise LookupError(f"no file {path!r} in package {package!r} (looked in {root})")
    return found


def resolve_package(package: str, path: str | None) -> tuple[Path, tuple[str, ...]]:
    r"""(URDF file, package folders) of ``path`` inside ``package`` (see the module table)."""
    if package == "wheeled-dyn":
        return _inside(urdf_dir(), path, package), ()
    if package == "example-robot-data":
        share = example_robot_data_share()
        if share is None:
            raise OptionalDependencyError("package example-robot-data", "example-robot-data",
                                          "pip install example-robot-data")
        return _inside(share / "example-robot-data", path, package), (str(share),)
    if package == "upkie-description":
        try:
            import upkie_description
        except ImportError:
            raise OptionalDependencyError("package upkie-description", "upkie-description",
                                          "pip install upkie-description") from None
        folder = Path(upkie_description.__file__).resolve().parent
        urdf = (Path(upkie_description.URDF_PATH) if path is None
                else _inside(folder, path, package))
        return urdf, (str(folder.parent),)
    raise LookupError(f"unknown package {package!r}; known: {', '.join(PACKAGES)}")


def package_reference(urdf: Path) -> tuple[str, str | None] | None:
    r"""``(package, path or None)`` naming ``urdf`` inside an installed package of
    :data:`PACKAGES` (the inverse of :func:`resolve_package`), or None."""
    urdf = resolved(urdf)
    try:
        import upkie_description
        if urdf == Path(upkie_description.URDF_PATH).resolve():
            return "upkie-description", None
    except ImportError:
        pass
    roots = [("wheeled-dyn", urdf_dir())]
    share = example_robot_data_share()
    if share is not None:
        roots.append(("example-robot-data", share / "example-robot-data"))
    for package, root in roots:
        try:
            return package, urdf.relative_to(root.resolve()).as_posix()
        except ValueError:
            continue
    return None
