r"""Property tests (hypothesis): random corruption of any cache entry never raises and never
changes a verdict (issue 25). An entry is read only if its signature is the cache key's for
its own name, and any failure while reading it is a miss (:mod:`wheeled_dyn.disk_cache`)."""

from __future__ import annotations

import os
import pickle
import shutil
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis", reason="property tests need hypothesis (the "
                                 "test extras)")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from wheeled_dyn import cache_trust, compiled, disk_cache  # noqa: E402
from wheeled_dyn.cli import compare_cmd as commands  # noqa: E402
from wheeled_dyn.compare.judge import document_checks  # noqa: E402
from wheeled_dyn.compare.other_documents import tables as seed_table  # noqa: E402
from wheeled_dyn.compare.presentation import printing, residuals  # noqa: E402
from wheeled_dyn.derivations import builtin_derivations  # noqa: E402
from wheeled_dyn.disk_cache import CACHE_ENV, MAGIC, REUSE_ENV, load, save_memos, store  # noqa: E402
from wheeled_dyn.models import registry  # noqa: E402
from wheeled_dyn.report import html_text, symbols  # noqa: E402
from wheeled_dyn.symbolic import wheeled  # noqa: E402

#: Examples of the quick property (one entry, read back) and of the slow one (a comparison).
QUICK_EXAMPLES, COMPARISON_EXAMPLES = 1000, 40
#: A small grid: the verdicts only have to be the same as from an intact cache.
SAMPLES, PARAM_SETS = 30, 1
MEMOS = (printing.PRINTED, residuals.RESIDUALS, document_checks.RESIDUALS, compiled.SOURCES,
         seed_table.SHOWN, symbols.RENDERED, html_text.MATHML)

#: A value with the kinds of objects entries hold.
VALUE = {"text": "x*cos(phi)**2", "numbers": (1.0, 2, None), "bytes": b"\x00\x01" * 40}


def _corrupt(data: bytes, how: str, at: int, span: bytes) -> bytes:
    r"""``data`` corrupted: one bit flipped, bytes overwritten, cut, extended, replaced."""
    at = at % max(len(data), 1)
    if how == "flip":
        return data[:at] + bytes([data[at] ^ (1 << (span[0] % 8 if span else 0))]) \
            + data[at + 1:]
    if how == "overwrite":
        return data[:at] + span + data[at + len(span):]
    if how == "truncate":
        return data[:at]
    if how == "extend":
        return data + span
    return span


CORRUPTIONS = st.tuples(st.sampled_from(["flip", "overwrite", "truncate", "extend", "replace"]),
                        st.integers(0, 10 ** 6), st.binary(min_size=1, max_size=64))


@pytest.fixture
def fresh(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(REUSE_ENV, "1")
    cache_trust.forget_keys()
    yield tmp_path / "cache"
    cache_trust.forget_keys()


@settings(max_examples=QUICK_EXAMPLES, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(corruption=CORRUPTIONS)
def test_a_corrupted_entry_is_a_miss_or_itself(fresh, corruption):
    entry = fresh / "results" / "entry.pickle"
    assert store(entry, VALUE)
    good = entry.read_bytes()
    bad = _corrupt(good, *corruption)
    entry.write_bytes(bad)
    found = load(entry, dict)                        # never raises
    assert found is None or (bad == good and found == VALUE)


#: Pickles that fail as they are read, each signed with the user's key (so that only the
#: reading, not the signature, can reject them): a frame length changed (the issue's 8 bytes),
#: a truncated stream, a huge BINBYTES8, an unknown opcode, a class that does not exist.
BAD_PICKLES = [
    pickle.dumps(VALUE, protocol=5)[:3] + (2 ** 62).to_bytes(8, "little")
    + pickle.dumps(VALUE, protocol=5)[11:],
    pickle.dumps(VALUE, protocol=5)[:-9],
    b"\x80\x05\x8e" + (2 ** 62).to_bytes(8, "little") + b"x.",
    b"\x80\x05\xff.",
    b"\x80\x04cno_such_module\nNoSuchClass\n)\x81.",
]


@pytest.mark.parametrize("payload", BAD_PICKLES, ids=range(len(BAD_PICKLES)))
def test_a_signed_entry_that_fails_to_unpickle_is_a_miss(fresh, payload):
    entry = fresh / "results" / "entry.pickle"
    assert store(entry, "anything")                  # the folder and the key
    key = cache_trust.signing_key(fresh)
    entry.write_bytes(MAGIC + disk_cache._signature(key, "results/entry.pickle", payload)
                      + payload)
    assert load(entry, object) is None


def _forget_memory() -> None:
    r"""What a new process does not have: memos, closed forms, models in memory."""
    for memo in MEMOS:
        memo.forget()
    wheeled._MEMORY.clear()
    registry._built.cache_clear()
    registry._spec_of.cache_clear()
    symbols._NOTATIONS.clear()
    html_text.mathml.cache_clear()


def _records(path: Path):
    _forget_memory()
    (result,) = commands.run_comparison([path], SAMPLES, PARAM_SETS)
    return result.records, result.causes


@pytest.fixture(scope="module")
def warm(tmp_path_factory):
    r"""A cache filled by one comparison (results, closed forms, URDF outline, compiled code,
    printed forms), a copy of its files, and the verdicts from an empty cache."""
    folder = tmp_path_factory.mktemp("corruption")
    path = next(p for p in builtin_derivations("seed000") if p.name == "p4_8_rolling_disk.toml")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(CACHE_ENV, str(folder / "cache"))
        mp.setenv(REUSE_ENV, "1")
        cache_trust.forget_keys()
        truth = _records(path)
        save_memos()
    files = sorted(p for p in (folder / "cache").rglob("*") if p.is_file())
    kinds = {p.parent.name for p in files}
    assert {"results", "symbolic", "urdf", "compiled", "compare"} <= kinds, kinds
    saved = folder / "saved"
    shutil.copytree(folder / "cache", saved)
    return path, folder / "cache", saved, files, truth


@settings(max_examples=COMPARISON_EXAMPLES, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(data=st.data())
def test_a_corrupted_cache_never_changes_a_verdict(warm, monkeypatch, data):
    path, root, saved, files, truth = warm
    monkeypatch.setenv(CACHE_ENV, str(root))
    monkeypatch.setenv(REUSE_ENV, "1")
    cache_trust.forget_keys()
    shutil.rmtree(root)
    shutil.copytree(saved, root)
    target = data.draw(st.sampled_from(files), label="entry")
    if data.draw(st.booleans(), label="another entry's bytes"):
        other = data.draw(st.sampled_from([f for f in files if f != target]), label="from")
        target.write_bytes(other.read_bytes())
    else:
        target.write_bytes(_corrupt(target.read_bytes(), *data.draw(CORRUPTIONS)))
    os.utime(target)
    assert _records(path) == truth                   # the result itself read (or not)
    monkeypatch.setenv(REUSE_ENV, "forms")           # compared again: every form read
    assert _records(path) == truth
    cache_trust.forget_keys()
