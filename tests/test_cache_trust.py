r"""The disk cache only saves time (issue 25, docs/cache.md): folders are created private
whatever the umask; a folder another user owns or can write is not used (one warning, the run
goes on); entries are signed with a private key, so a planted, altered or copied entry is never
loaded (a planted pickle is never unpickled); ``WHEELED_DYN_REUSE=0`` reads no remembered
result and no remembered code; a cache that cannot be written makes a run slower, never fail.

Another user is played by a uid the check does not run as: the files are given to uid
:data:`OTHER_UID` when the tests run as root, else the check is told to run as another uid.
"""

from __future__ import annotations

import errno
import hashlib
import hmac
import os
import pickle
import stat
import warnings
from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn import cache_trust, compiled, disk_cache
from wheeled_dyn.cli import compare_cmd as commands
from wheeled_dyn.compare.other_documents import tables as seed_table
from wheeled_dyn.compare.presentation import printing, residuals
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.runtime.result_cache import result_key
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.disk_cache import CACHE_ENV, MAGIC, REUSE_ENV, load, save_memos, store
from wheeled_dyn.errors import CacheWarning

#: The uid that plays another user.
OTHER_UID = 65534
#: A small grid: the tests are about where numbers come from, not about the verdicts.
SAMPLES, PARAM_SETS = 30, 1
MEMOS = (printing.PRINTED, residuals.RESIDUALS, compiled.SOURCES, seed_table.SHOWN)


@pytest.fixture
def cache(tmp_path, monkeypatch):
    r"""Reuse on, in a fresh cache folder (not made yet); warnings and keys forgotten."""
    root = tmp_path / "cache"
    monkeypatch.setenv(CACHE_ENV, str(root))
    monkeypatch.setenv(REUSE_ENV, "1")
    cache_trust.forget_keys()
    for memo in MEMOS:
        memo.forget()
    yield root
    cache_trust.forget_keys()
    for memo in MEMOS:
        memo.forget()


def _another_user(path: Path, monkeypatch) -> None:
    r"""Make ``path`` another user's (really, as root; else the check runs as another uid)."""
    if os.geteuid() == 0:
        os.chown(path, OTHER_UID, OTHER_UID)
    else:
        monkeypatch.setattr(cache_trust, "_uid", lambda: os.geteuid() + 1)


def _derivation(name: str = "p4_8_rolling_disk.toml", group: str = "seed000") -> Path:
    return next(p for p in builtin_derivations(group) if p.name == name)


def _verdicts(result) -> dict[str, str]:
    return {r.element: r.verdict for r in result.records}


def _cache_warnings(record) -> list[str]:
    return [str(w.message) for w in record if issubclass(w.category, CacheWarning)]


def test_folders_and_files_are_private_whatever_the_umask(cache):
    old = os.umask(0)
    try:
        assert store(cache / "results" / "x.pickle", {"a": 1})
    finally:
        os.umask(old)
    for folder in (cache, cache / "results"):
        assert stat.S_IMODE(folder.stat().st_mode) == 0o700, folder
    for file in (cache / cache_trust.KEY_NAME, cache / "results" / "x.pickle"):
        assert stat.S_IMODE(file.stat().st_mode) == 0o600, file
    assert load(cache / "results" / "x.pickle", dict) == {"a": 1}


@pytest.mark.parametrize("how", ["writable by others", "writable by its group",
                                 "another user's", "inside a folder others can write"])
def test_a_folder_another_user_could_write_is_not_used(cache, monkeypatch, how):
    entry = cache / "results" / "x.pickle"
    assert store(entry, "remembered")
    assert load(entry, str) == "remembered"
    if how == "writable by others":
        cache.chmod(0o777)
    elif how == "writable by its group":
        (cache / "results").chmod(0o770)
    elif how == "another user's":
        _another_user(cache, monkeypatch)
    else:
        cache.parent.chmod(0o777)                   # no sticky bit: others may rename it
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        assert load(entry, str) is None             # not read
        assert not store(cache / "results" / "y.pickle", "new")     # not written
        assert load(entry, str) is None
    said = _cache_warnings(record)
    assert len(said) == 1, said                     # one warning line, once
    assert str(cache) in said[0] and "not used" in said[0]
    assert not (cache / "results" / "y.pickle").exists()
    cache.parent.chmod(0o700)


def test_a_sticky_world_writable_folder_above_is_accepted(cache, monkeypatch):
    r"""``/tmp`` is world-writable with the sticky bit: a private cache inside it is used."""
    cache.parent.chmod(0o1777)
    try:
        assert store(cache / "results" / "x.pickle", "v")
        assert load(cache / "results" / "x.pickle", str) == "v"
    finally:
        cache.parent.chmod(0o700)


def test_a_damaged_key_is_replaced_and_its_entries_are_misses(cache):
    entry = cache / "results" / "x.pickle"
    assert store(entry, "remembered")
    key = cache / cache_trust.KEY_NAME
    key.write_bytes(b"short")
    cache_trust.forget_keys()
    with warnings.catch_warnings():
        warnings.simplefilter("error")            # no warning: only slower
        assert load(entry, str) is None
        assert store(entry, "again")              # a new key
    assert len(key.read_bytes()) == cache_trust.KEY_BYTES
    assert stat.S_IMODE(key.stat().st_mode) == 0o600
    assert load(entry, str) == "again"


@pytest.mark.parametrize("how", ["readable by others", "another user's"])
def test_a_key_that_is_not_private_turns_the_cache_off(cache, monkeypatch, how):
    entry = cache / "results" / "x.pickle"
    assert store(entry, "remembered")
    key = cache / cache_trust.KEY_NAME
    cache_trust.forget_keys()
    if how == "readable by others":
        key.chmod(0o644)
    elif how == "another user's":
        if os.geteuid() != 0:
            pytest.skip("needs root to give the key to another user (the folder check comes "
                        "first otherwise)")
        os.chown(key, OTHER_UID, OTHER_UID)
    with pytest.warns(CacheWarning, match="not private"):
        assert load(entry, str) is None


class Planted:
    r"""What a planted pickle runs when it is loaded: it creates a file."""

    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self):
        return open, (str(self.marker), "w")


def _planted(marker: Path) -> bytes:
    return pickle.dumps(Planted(marker))


def test_a_planted_pickle_is_never_unpickled(cache, tmp_path):
    r"""Pickles written into the user's own results folder under the key of the next run —
    unsigned, with a made-up signature, signed with another key — are never loaded (the
    signature is checked first): the derivation is compared, and nothing the pickle would
    run happens."""
    path = _derivation()
    marker = tmp_path / "ran"
    assert pickle.loads(_planted(marker)) and marker.exists()     # the pickle does run
    marker.unlink()
    grid = (SAMPLES, PARAM_SETS, 2026)
    truth = _verdicts(ComparisonEngine(SAMPLES, PARAM_SETS).compare(load_derivation(path)))
    assert store(cache / "results" / "warm.pickle", 0)            # the key exists
    entry = cache / "results" / f"{result_key(path, 'rolling_disk', grid)}.pickle"
    payload = _planted(marker)
    name = f"results/{entry.name}".encode()
    plants = [payload, MAGIC + bytes(32) + payload,
              MAGIC + hmac.new(b"k" * 32, name + b"\0" + payload, hashlib.sha256).digest()
              + payload]
    for plant in plants:
        entry.write_bytes(plant)
        (result,) = commands.run_comparison([path], SAMPLES, PARAM_SETS)
        assert not marker.exists()
        assert _verdicts(result) == truth
        entry.unlink()
    # the control: signed with the user's own key, it is loaded from exactly that place
    key = cache_trust.signing_key(cache)
    entry.write_bytes(MAGIC + hmac.new(key, name + b"\0" + payload, hashlib.sha256).digest()
                      + payload)
    commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert marker.exists()


def test_a_pickle_planted_by_another_user_in_a_shared_folder_is_not_read(cache, tmp_path,
                                                                          monkeypatch):
    r"""The issue's case: a cache folder others can write (as ``umask 000`` made them before),
    another user's pickle and key in it. The check warns once, runs without the cache, and
    prints its own verdicts; the pickle never runs."""
    path = _derivation()
    marker = tmp_path / "ran"
    grid = (SAMPLES, PARAM_SETS, 2026)
    truth = _verdicts(ComparisonEngine(SAMPLES, PARAM_SETS).compare(load_derivation(path)))
    folder = cache / "results"
    folder.mkdir(parents=True)
    cache.chmod(0o777)
    folder.chmod(0o777)
    key = b"k" * 32                                   # the other user's key, planted too
    (cache / cache_trust.KEY_NAME).write_bytes(key)
    entry = folder / f"{result_key(path, 'rolling_disk', grid)}.pickle"
    payload = _planted(marker)
    entry.write_bytes(MAGIC + hmac.new(key, f"results/{entry.name}".encode() + b"\0" + payload,
                                       hashlib.sha256).digest() + payload)
    for p in (entry, cache / cache_trust.KEY_NAME, folder):
        if os.geteuid() == 0:
            os.chown(p, OTHER_UID, OTHER_UID)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        (result,) = commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert not marker.exists()
    assert _verdicts(result) == truth
    said = _cache_warnings(record)
    assert len(said) == 1 and "can be written by other users" in said[0], said


def _compared(path: Path):
    for memo in MEMOS:
        memo.forget()
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))


def _tampered_sources() -> tuple[Path, dict]:
    r"""The compiled-code memo's entries with every ``1/3`` made ``2/3`` (the issue's case)."""
    path = compiled.SOURCES.path()
    entries = load(path, dict)
    changed = {k: (src.replace("1/3", "2/3"), imports) for k, (src, imports) in entries.items()}
    assert changed != entries, "the derivation's compiled code holds a 1/3"
    return path, changed


def test_remembered_code_altered_on_disk_is_not_run(cache):
    r"""Seed 000's rod pendulum (a 1/3 in its inertia): its compiled code altered on disk
    (1/3 → 2/3). Altered without the key, it is never run; re-signed with the user's own key
    (only the user can), it is run only when reuse is on — ``WHEELED_DYN_REUSE=0`` and
    ``without_reuse`` run none of it. The control (reuse on, validly signed) shows that the
    altered code would change the verdicts."""
    path = _derivation("p4_4_rod_pendulum.toml")
    truth = _verdicts(_compared(path))
    save_memos()
    memo_file, changed = _tampered_sources()
    signed = memo_file.read_bytes()
    head = len(MAGIC) + 32
    memo_file.write_bytes(signed[:head] + pickle.dumps(changed))     # altered, old signature
    assert _verdicts(_compared(path)) == truth
    assert store(memo_file, changed)                                  # re-signed by the user
    assert _verdicts(_compared(path)) != truth                        # the control
    os.environ[REUSE_ENV] = "0"
    try:
        assert _verdicts(_compared(path)) == truth
        assert compiled.SOURCES.entries() is compiled.SOURCES._unkept  # nothing from disk
    finally:
        os.environ[REUSE_ENV] = "1"
    with cache_trust.without_reuse():
        assert _verdicts(_compared(path)) == truth


def test_reuse_off_reads_no_remembered_result(cache, monkeypatch):
    path = _derivation()
    commands.run_comparison([path], SAMPLES, PARAM_SETS)             # stored
    calls = []
    original = ComparisonEngine.compare
    monkeypatch.setattr(ComparisonEngine, "compare",
                        lambda self, d: calls.append(1) or original(self, d))
    commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert calls == []                                                # reused
    with cache_trust.without_reuse():
        commands.run_comparison([path], SAMPLES, PARAM_SETS)
    monkeypatch.setenv(REUSE_ENV, "0")
    commands.run_comparison([path], SAMPLES, PARAM_SETS)
    assert calls == [1, 1]


@pytest.mark.parametrize("how", ["missing", "full", "read-only"])
def test_a_cache_that_cannot_be_written_only_slows_the_run(cache, tmp_path, monkeypatch, how):
    r"""A cache folder that cannot be created (its place is a file), a full disk, a read-only
    file system: the comparison runs to its end with the same verdicts, and says so once,
    naming the folder."""
    path = _derivation()
    truth = _verdicts(ComparisonEngine(SAMPLES, PARAM_SETS).compare(load_derivation(path)))
    if how == "missing":
        (tmp_path / "file").write_text("a file, not a folder")
        monkeypatch.setenv(CACHE_ENV, str(tmp_path / "file" / "cache"))
        folder = str(tmp_path / "file" / "cache")
    else:
        code = errno.ENOSPC if how == "full" else errno.EROFS

        def refuse(*args, **kwargs):
            raise OSError(code, os.strerror(code))
        monkeypatch.setattr(disk_cache.tempfile, "mkstemp", refuse)
        folder = str(cache)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        for _ in range(2):
            (result,) = commands.run_comparison([path], SAMPLES, PARAM_SETS)
            assert _verdicts(result) == truth
        save_memos()
    said = _cache_warnings(record)
    assert len(said) == 1, said
    assert folder in said[0] and "only slower" in said[0]
    if how != "missing":
        assert not list(cache.rglob("*.pickle"))
        assert not list(cache.rglob(".tmp-*"))


def test_an_entry_over_the_size_bound_is_a_miss(cache, monkeypatch):
    entry = cache / "results" / "x.pickle"
    assert store(entry, "x" * 1000)
    monkeypatch.setattr(disk_cache, "MAX_ENTRY_BYTES", 500)
    assert load(entry, str) is None


def test_an_entry_that_is_a_folder_is_named_when_it_cannot_be_replaced(cache):
    r"""A folder in an entry's place: its result is not kept, and the warning names the entry
    (it said the cache folder could not be written, a folder that is fine: the next entry
    beside it is written)."""
    entry = cache / "results" / "x.pickle"
    assert store(entry, "remembered")
    entry.unlink()
    entry.mkdir()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert not store(entry, "remembered")
    said = [str(w.message) for w in caught]
    assert len(said) == 1 and f"the cache entry {entry} is a folder, not a file" in said[0], said
    assert store(cache / "results" / "y.pickle", "next") and \
        load(cache / "results" / "y.pickle", str) == "next"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")
def test_an_entry_that_is_a_fifo_or_a_folder_is_a_miss_at_once(cache):
    r"""An entry replaced by a FIFO (whose opening waited for a writer: the run hung) or by
    a folder is a miss, without waiting."""
    import subprocess
    import sys
    entry = cache / "results" / "x.pickle"
    assert store(entry, "remembered")
    entry.unlink()
    os.mkfifo(entry)
    probe = ("import sys; from pathlib import Path; from wheeled_dyn.disk_cache import load; "
             "print(load(Path(sys.argv[1]), str))")
    done = subprocess.run([sys.executable, "-c", probe, str(entry)], capture_output=True,
                          text=True, timeout=60, env=os.environ)
    assert done.stdout.strip() == "None", done.stderr
    entry.unlink()
    entry.mkdir()
    assert load(entry, str) is None


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")
@pytest.mark.parametrize("kind", ["folder", "fifo"])
def test_a_key_that_is_not_a_file_turns_the_cache_off_with_one_warning(cache, kind):
    r"""The signing key replaced by a folder (the run failed: "Is a directory") or a FIFO (it
    would wait): one warning, and the run goes on without the cache."""
    entry = cache / "results" / "x.pickle"
    assert store(entry, "remembered")
    key = cache / cache_trust.KEY_NAME
    key.unlink()
    key.mkdir() if kind == "folder" else os.mkfifo(key)
    cache_trust.forget_keys()
    with pytest.warns(CacheWarning, match="not a regular file"):
        assert load(entry, str) is None
    assert not store(entry, "again")


def test_the_no_cache_flag_reads_and_writes_nothing(tmp_path):
    r"""``compare --no-cache`` with reuse on in the environment: the cache folder is not even
    created (nothing read, nothing written), and the verdicts are printed."""
    import subprocess
    import sys
    root = tmp_path / "cache"
    env = {**os.environ, CACHE_ENV: str(root), REUSE_ENV: "1"}
    out = subprocess.run([sys.executable, "-m", "wheeled_dyn.cli.main", "compare", "rolling_disk",
                          str(_derivation()), "--no-cache", "--samples", str(SAMPLES),
                          "--param-sets", str(PARAM_SETS), "--out", str(tmp_path / "out")],
                         capture_output=True, text=True, env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    assert " agree, " in out.stdout
    assert not root.exists()


def test_the_command_warns_once_and_gives_the_verdicts(tmp_path):
    r"""``compare`` of eq. (25) (its step files compared in a forked worker) with a cache folder
    others can write: one warning line naming the folder, the verdicts of a run without it,
    exit code 0, nothing written there."""
    import subprocess
    import sys
    root = tmp_path / "cache"
    root.mkdir()
    root.chmod(0o777)
    eq25 = _derivation("eq25_lagrange.toml", "seed001")
    command = [sys.executable, "-m", "wheeled_dyn.cli.main", "compare", "wip", str(eq25),
               "--samples", str(SAMPLES), "--param-sets", str(PARAM_SETS),
               "--out", str(tmp_path / "out")]
    shared = subprocess.run(command, capture_output=True, text=True, timeout=300,
                            env={**os.environ, CACHE_ENV: str(root), REUSE_ENV: "1"})
    alone = subprocess.run([*command, "--no-cache"], capture_output=True, text=True,
                           timeout=300, env={**os.environ, CACHE_ENV: str(root)})
    assert shared.returncode == 0 and alone.returncode == 0, shared.stderr + alone.stderr
    lines = [line for line in shared.stderr.splitlines() if line]
    assert len(lines) == 1 and lines[0].startswith("wheeled-dyn: warning: the cache folder "
                                                   f"{root} can be written by other users")
    assert shared.stdout.replace(str(tmp_path), "") == alone.stdout.replace(str(tmp_path), "")
    assert list(root.iterdir()) == []
