"""On-disk cache of symbolic models: hits return the same closed forms, the key follows the
model's content, unreadable entries are derived again and replaced."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from test_symbolic_model import SEED, arm3, wip_like

from wheeled_dyn.disk_cache import MAGIC, REUSE_ENV
from wheeled_dyn.symbolic import numeric_parameters
from wheeled_dyn.symbolic.cache import (
    CACHE_ENV, cache_dir, cached_symbolic_model, clear_cache, model_fingerprint)


@pytest.fixture
def root(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(REUSE_ENV, "1")
    return tmp_path / "cache"


def test_cache_dir_follows_the_environment(root):
    assert cache_dir() == root / "symbolic"


def test_second_call_is_a_hit_with_equal_results(root):
    model = arm3(np.random.default_rng(SEED))
    first = cached_symbolic_model(model)
    files = list((root / "symbolic").glob("*.pickle"))
    assert len(files) == 1
    mtime = files[0].stat().st_mtime_ns
    second = cached_symbolic_model(model)
    assert files[0].stat().st_mtime_ns == mtime
    assert second is not first
    assert second.A == first.A and second.Q == first.Q and second.h() == first.h()
    assert second.christoffel() == first.christoffel()
    assert second.q == first.q and second.parameters == first.parameters


def test_key_follows_the_content(root):
    rng = np.random.default_rng(SEED)
    model = wip_like(rng)
    key = model_fingerprint(model)
    assert model_fingerprint(pin.Model(model)) == key
    moved = pin.Model(model)
    moved.jointPlacements[4] = pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.31]))
    assert model_fingerprint(moved) != key
    assert model_fingerprint(model, coordinate_names=list("abcdef")) != key
    assert model_fingerprint(model, gravity="g") != key
    assert model_fingerprint(model, simplify=False) != key
    # with symbolic parameters the model's inertias do not matter; with numbers they do
    heavier = pin.Model(model)
    heavier.inertias[4] = pin.Inertia.Random()
    assert model_fingerprint(heavier) == key
    assert model_fingerprint(heavier, params=numeric_parameters(heavier)) != \
        model_fingerprint(model, params=numeric_parameters(model))


def test_unreadable_entry_is_replaced(root):
    model = arm3(np.random.default_rng(SEED))
    path = root / "symbolic" / f"{model_fingerprint(model)}.pickle"
    path.parent.mkdir(parents=True)
    path.write_bytes(b"not a pickle")
    sym = cached_symbolic_model(model)                      # a miss: derived again
    assert sym.n == 3
    assert path.read_bytes().startswith(MAGIC)              # replaced by a signed entry
    assert cached_symbolic_model(model).A == sym.A
    assert clear_cache() == 1
    assert not path.exists()


def test_refresh_rewrites(root):
    model = arm3(np.random.default_rng(SEED))
    cached_symbolic_model(model)
    path = next((root / "symbolic").glob("*.pickle"))
    before = path.stat().st_mtime_ns
    cached_symbolic_model(model, refresh=True)
    assert path.stat().st_mtime_ns >= before
    assert len(list((root / "symbolic").glob("*"))) == 1  # no temporary files left


def test_the_closed_forms_follow_which_joint_each_input_drives(root, tmp_path):
    r"""The two-link arm's model file with its inputs' joints swapped (``actuated = ["elbow",
    "shoulder"]``): its closed forms are derived again, not read back — the corrected
    equations of a document ended ``= tau1`` where the truth reads ``= tau2`` (the key held
    the inputs' names, not their joints). The same as with no cache at all."""
    from pathlib import Path

    import wheeled_dyn as wd
    from wheeled_dyn.models.registry import load_model
    from wheeled_dyn.symbolic import true_expressions
    data = Path(__file__).parent / "data" / "two_link_arm"
    for name in ("two_link_arm.toml", "two_link_arm.urdf"):
        (tmp_path / name).write_text((data / name).read_text())
    model = tmp_path / "two_link_arm.toml"

    def B_of_first_row() -> str:
        cs = wd.builtin_coordinate_set(load_model(str(model)))
        truth = true_expressions(str(model), cs)
        assert truth is not None
        return str({k: v for k, v in truth.items() if k.startswith("B")})

    first = B_of_first_row()
    text = model.read_text()
    assert 'actuated = ["shoulder", "elbow"]' in text
    model.write_text(text.replace('actuated = ["shoulder", "elbow"]',
                                  'actuated = ["elbow", "shoulder"]'))
    swapped = B_of_first_row()
    assert swapped != first, (first, swapped)
