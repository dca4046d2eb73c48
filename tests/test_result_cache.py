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


def _entries(tmp_path):
    return sorted((tmp_path / "cache" / "results").glob("*.pickle"))


def test_an_entry_copied_under_another_key_is_not_served(tmp_path, counted):
    r"""Two derivations' entries swapped (each file renamed to the other's key): neither is
    taken (the signature covers the entry's own name, and the entry holds its key), both are
    compared again, with their own verdicts."""
    one = _copy(tmp_path)
    two = one.with_name("twin.toml")
    two.write_text(one.read_text().replace("- m*r**2)", "+ m*r**2)"))
    first = {p.name: r for p, r in zip([one, two], commands.run_comparison(
        [one, two], SAMPLES, PARAM_SETS))}
    a, b = _entries(tmp_path)
    data_a, data_b = a.read_bytes(), b.read_bytes()
    a.write_bytes(data_b)
    b.write_bytes(data_a)
    again = {r.path.name: r for r in commands.run_comparison([one, two], SAMPLES, PARAM_SETS)}
    assert counted == [one.name, two.name, one.name, two.name]
    for name in (one.name, two.name):
        assert again[name].records == first[name].records
    assert {r.element: r.verdict for r in again[one.name].records}["A[1,1]"] == "differs"
    assert {r.element: r.verdict for r in again[two.name].records}["A[1,1]"] == "agrees"


def test_a_result_is_stored_only_if_its_files_did_not_change_meanwhile(tmp_path, counted,
                                                                         monkeypatch):
    r"""The derivation file saved while it is compared (after it was parsed): the result of
    the old text is returned but not stored under the new text's key; the next run compares
    the new text."""
    path = _copy(tmp_path)
    text = path.read_text()
    original = ComparisonEngine.compare

    def saved_meanwhile(self, d):
        path.write_text(text.replace("- m*r**2)", "+ m*r**2)"))
        return original(self, d)
    monkeypatch.setattr(ComparisonEngine, "compare", saved_meanwhile)
    (old,) = commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert {r.element: r.verdict for r in old.records}["A[1,1]"] == "differs"
    assert _entries(tmp_path) == []
    monkeypatch.setattr(ComparisonEngine, "compare", original)
    (new,) = commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert {r.element: r.verdict for r in new.records}["A[1,1]"] == "agrees"


def test_the_key_covers_the_model_file_and_its_urdf(tmp_path):
    from wheeled_dyn.compare.runtime.result_cache import dependencies, result_key
    from wheeled_dyn.models.registry import MODELS, model_files
    path = _copy(tmp_path)
    model = "rolling_disk"
    files = model_files(model)
    assert MODELS[model].source in files and any(f.suffix == ".urdf" for f in files)
    assert set(files) <= set(dependencies(path, model))
    key = result_key(path, model, (1, 2, 3))
    assert result_key(path, model, (1, 2, 3), extra=[path.parent / "new.toml"]) != key
    assert result_key(path, model, (1, 2, 4)) != key


def test_the_package_digest_covers_the_whole_package():
    r"""Every file of the package is in the key (the digest's folder is the package's, not
    that of the module computing it)."""
    import wheeled_dyn
    from pathlib import Path
    from wheeled_dyn.compare.runtime import result_cache
    assert result_cache._PACKAGE == Path(wheeled_dyn.__file__).resolve().parent
