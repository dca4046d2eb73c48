r"""A file rewritten in place — the same inode, the same size, its modification time set back
(a tool that restores times, a sync, a checkout at a coarse clock) — is another file for every
memo of the process: the model built from a URDF, a step file parsed, a derivation's result.

The memos were keyed by (mtime, size, inode) only: in one process (the Python API, ``compare
--watch``) a URDF whose wheel axis was turned in place kept its old truth, and ``--watch``
then stored that stale result in the disk cache under the new content's key. The stamp now
holds the change time as well, which every write moves and no program sets back.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np

from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.models.model_joints import joint_axis
from wheeled_dyn.models.registry import load_model
from wheeled_dyn.paths import file_stamp

DATA = Path(__file__).parent / "data" / "ros_balancer"
AXIS, TURNED = '<axis xyz="0 -1 0"/>', '<axis xyz="0 1 00"/>'


def _rewrite_in_place(path: Path, old: str, new: str) -> None:
    r"""``old`` replaced by ``new`` (the same length) in place, the times set back."""
    before = os.stat(path)
    text = path.read_text()
    assert old in text and len(old) == len(new)
    with open(path, "r+") as handle:
        handle.write(text.replace(old, new, 1))
    os.utime(path, ns=(before.st_atime_ns, before.st_mtime_ns))
    after = os.stat(path)
    assert (after.st_ino, after.st_size, after.st_mtime_ns) == \
        (before.st_ino, before.st_size, before.st_mtime_ns)


def _copy(tmp_path: Path) -> tuple[Path, Path]:
    for name in ("ros_balancer.toml", "ros_balancer.urdf", "ros_balancer_heading.toml"):
        shutil.copy(DATA / name, tmp_path / name)
    return tmp_path / "ros_balancer.toml", tmp_path / "ros_balancer.urdf"


def _right_axis(model: Path) -> np.ndarray:
    wm = load_model(str(model))
    return joint_axis(wm.model.joints[wm.wheels[1].joint_id])


def test_a_stamp_changes_with_an_in_place_rewrite(tmp_path):
    _, urdf = _copy(tmp_path)
    before = file_stamp(urdf)
    _rewrite_in_place(urdf, AXIS, TURNED)
    assert file_stamp(urdf) != before


def test_a_urdf_rewritten_in_place_gives_a_new_model_and_truth(tmp_path):
    model, urdf = _copy(tmp_path)
    assert AXIS in urdf.read_text()
    before = _right_axis(model)
    derivation = load_derivation(tmp_path / "ros_balancer_heading.toml")
    first = ComparisonEngine(samples=100, param_sets=2).compare(derivation)
    assert first.equivalent is True
    _rewrite_in_place(urdf, AXIS, TURNED)           # the right wheel's axis turned
    assert not np.allclose(_right_axis(model), before)
    again = ComparisonEngine(samples=100, param_sets=2).compare(
        load_derivation(tmp_path / "ros_balancer_heading.toml"))
    assert any(r.verdict == Verdict.DIFFERS for r in again.records)
    assert again.equivalent is False
