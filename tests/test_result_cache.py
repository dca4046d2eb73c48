r"""Comparison results are reused from the disk cache when nothing they depend on changed
(compare/result_cache.py): the same file gives the stored result without comparing again;
a change to the file, to a step file beside it, or to the grid gives a new comparison."""

from __future__ import annotations

import shutil

import pytest

from wheeled_dyn.cli import compare_cmd as commands
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.runtime.result_cache import REUSE_ENV
from wheeled_dyn.derivations import builtin_derivations
from wheeled_dyn.disk_cache import CACHE_ENV

SAMPLES, PARAM_SETS = 30, 1


@pytest.fixture
def counted(monkeypatch, tmp_path):
    r"""Reuse on, in a fresh cache; counts the comparisons the engine really makes."""
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(REUSE_ENV, "1")
    calls = []
    original = ComparisonEngine.compare

    def compare(self, d):
        calls.append(d.path.name)
        return original(self, d)
    monkeypatch.setattr(ComparisonEngine, "compare", compare)
    return calls


def _copy(tmp_path, name="p4_8_rolling_disk.toml"):
    src = next(p for p in builtin_derivations("seed000") if p.name == name)
    folder = tmp_path / "docs"
    folder.mkdir(exist_ok=True)
    shutil.copy(src, folder / name)
    return folder / name


def test_a_result_is_reused_until_its_file_changes(tmp_path, counted):
    path = _copy(tmp_path)
    first = commands.run_comparison([path], SAMPLES, PARAM_SETS)
    again = commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert counted == [path.name]                        # the second came from the cache
    assert [r.verdict for r in again[0].records] == [r.verdict for r in first[0].records]
    text = path.read_text()
    assert text.count("- m*r**2)") == 1
    path.write_text(text.replace("- m*r**2)", "+ m*r**2)"))
    changed = commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert counted == [path.name, path.name]
    assert {r.element: r.verdict for r in changed[0].records}["A[1,1]"] == "agrees"
    assert {r.element: r.verdict for r in first[0].records}["A[1,1]"] == "differs"


def test_a_step_file_or_the_grid_changes_the_key(tmp_path, counted):
    path = _copy(tmp_path)
    commands.run_comparison([path], SAMPLES, PARAM_SETS)
    steps = next(p for p in builtin_derivations("seed000")).parent / "p4_12_energy_steps.toml"
    shutil.copy(steps, path.parent / steps.name)          # a step file appears beside it
    commands.run_comparison([path], SAMPLES, PARAM_SETS)
    commands.run_comparison([path], SAMPLES + 1, PARAM_SETS)
    assert len(counted) == 3


def test_reuse_can_be_turned_off(tmp_path, counted, monkeypatch):
    monkeypatch.setenv(REUSE_ENV, "0")
    path = _copy(tmp_path)
    for _ in range(2):
        commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert len(counted) == 2
