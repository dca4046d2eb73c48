r"""Printed forms remembered on disk (:class:`wheeled_dyn.disk_cache.DiskMemo`): a value is
computed once per key, read back by a new process, never served to other code, and a
comparison made from remembered forms is the comparison made from scratch."""

from __future__ import annotations

import numpy as np
import sympy as sp

from conftest import SEED
from wheeled_dyn import compiled
from wheeled_dyn.compare.judge import document_checks
from wheeled_dyn.compare.other_documents import tables as seed_table
from wheeled_dyn.compare.presentation import printing, residuals
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.disk_cache import CACHE_ENV, MAGIC, DiskMemo, load, save_memos

x, phi = sp.symbols("x phi", real=True)
#: The memos a comparison fills (all of them are emptied between the two runs below).
MEMOS = (printing.PRINTED, residuals.RESIDUALS, document_checks.RESIDUALS, compiled.SOURCES,
         seed_table.SHOWN)


def _memo(tmp_path, name="t", code_text="a = 1\n"):
    code = tmp_path / f"{name}.py"
    code.write_text(code_text)
    return DiskMemo("test", name, lambda: [code]), code


def test_a_value_is_computed_once_and_read_back_by_a_new_memo(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    memo, code = _memo(tmp_path)
    calls = []
    expr = x * sp.cos(phi) ** 2 + sp.Rational(1, 3)

    def compute():
        calls.append(1)
        return sp.sstr(expr)

    assert memo.get((expr, "names"), compute) == sp.sstr(expr)
    assert memo.get((x * sp.cos(phi) ** 2 + sp.Rational(1, 3), "names"), compute) \
        == sp.sstr(expr)
    assert len(calls) == 1
    memo.save()
    assert memo.path().is_file()
    again = DiskMemo("test", "t", lambda: [code])          # another process: only the file
    assert again.get((expr, "names"), compute) == sp.sstr(expr)
    assert len(calls) == 1
    assert again.get((expr, "other names"), compute) == sp.sstr(expr)
    assert len(calls) == 2


def test_a_memo_file_keeps_its_newest_entries_within_its_bytes(tmp_path, monkeypatch):
    r"""Entries of 100 kB each, far more than :data:`MEMO_BYTES` holds: the file stays within
    it (every command reads it whole: one of 33 MB took a quarter of a second at every
    start), and keeps the newest — an old entry used again counts as new."""
    from wheeled_dyn import disk_cache
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    memo, code = _memo(tmp_path)
    big = 100_000
    count = 2 * disk_cache.MEMO_BYTES // big
    for i in range(count):
        memo.get(("entry", i), lambda i=i: str(i) * (big // len(str(i))))
    memo.save()
    size = memo.path().stat().st_size
    assert size <= disk_cache.MEMO_BYTES + 2 ** 16, size
    again = DiskMemo("test", "t", lambda: [code])
    kept = again.entries()
    assert 0 < len(kept) < count
    made = []
    assert again.get(("entry", count - 1), lambda: made.append(1) or "x") != "x"  # newest kept
    oldest = next(i for i in range(count) if again.get(("entry", i), lambda: None) is not None)
    again.get(("new", 0), lambda: "n" * big)     # a new entry, and the oldest kept used again
    again.save()
    third = DiskMemo("test", "t", lambda: [code])
    assert third.get(("entry", oldest), lambda: made.append(2) or "gone") != "gone"
    assert not made

def test_values_of_other_code_are_not_served_and_their_file_goes(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    memo, code = _memo(tmp_path)
    memo.get("key", lambda: "old code's value")
    memo.save()
    old_file = memo.path()
    code.write_text("a = 2\n")                             # the code that computes changed
    fresh = DiskMemo("test", "t", lambda: [code])
    assert fresh.path() != old_file
    assert fresh.get("key", lambda: "new code's value") == "new code's value"
    fresh.save()
    assert fresh.path().is_file() and not old_file.exists()


def test_code_changed_while_running_keeps_nothing_and_a_missing_file_is_only_slower(
        tmp_path, monkeypatch):
    r"""Entries made by the code as it was when the memo was first read are never saved under
    the digest of code edited since (they would be served as the new code's); a code file
    that went away makes the memo compute without remembering, and save nothing, without an
    error (saving runs at exit)."""
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    memo, code = _memo(tmp_path)
    memo.get("key", lambda: "old code's value")
    code.write_text("a = 2\n")                             # edited during the run
    memo.save()
    assert not memo.path().exists()
    fresh = DiskMemo("test", "t", lambda: [code])
    assert fresh.get("key", lambda: "new code's value") == "new code's value"
    code.unlink()                                          # removed during the run
    fresh.save()
    save_memos()
    gone = DiskMemo("test", "gone", lambda: [tmp_path / "missing.py"])
    assert gone.get("k", lambda: "v") == "v" and gone.get("k", lambda: "w") == "v"
    gone.save()
    assert not (tmp_path / "cache").exists() or not any((tmp_path / "cache").rglob("gone-*"))


def test_a_key_that_cannot_be_pickled_is_computed_each_time(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    memo, _ = _memo(tmp_path)
    key = ("unpicklable", lambda: None)
    calls = []
    for _ in range(2):
        assert memo.get(key, lambda: calls.append(1) or "v") == "v"
    assert len(calls) == 2


def test_an_unreadable_file_is_only_slower(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    memo, _ = _memo(tmp_path)
    memo.path().parent.mkdir(parents=True)
    memo.path().write_bytes(b"not a pickle")
    assert memo.get("k", lambda: "v") == "v"
    memo.save()
    assert memo.path().read_bytes().startswith(MAGIC)       # replaced by a signed entry
    assert len(load(memo.path(), dict)) == 1


def test_compiled_code_read_back_is_lambdify_code(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    compiled.SOURCES.forget()
    expr = [x * sp.sin(phi), sp.Integer(2), sp.sqrt(x ** 2 + 1) * sp.cos(phi) ** 2]
    rng = np.random.default_rng(SEED)
    argv = [rng.uniform(0.5, 2.0, 20) for _ in range(2)]
    reference = sp.lambdify([x, phi], expr, "numpy")(*argv)
    fresh = compiled.numpy_function([x, phi], expr)(*argv)
    save_memos()
    compiled.SOURCES.forget()                              # a new process: the file only
    remembered = compiled.numpy_function([x, phi], expr)(*argv)
    assert len(compiled.SOURCES.entries()) == 1
    for a, b, c in zip(reference, fresh, remembered):
        assert np.array_equal(np.broadcast_to(a, (20,)), np.broadcast_to(b, (20,)))
        assert np.array_equal(np.broadcast_to(a, (20,)), np.broadcast_to(c, (20,)))
    compiled.SOURCES.forget()


def test_a_comparison_from_remembered_forms_is_the_comparison_from_scratch(tmp_path,
                                                                           monkeypatch):
    r"""Seed 001's Kim eq. (6)-(8) (a derivation with differing elements, so residuals are
    printed): the records computed with every memo empty, and again in a 'new process'
    reading them from disk, are equal."""
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    path = next(p for p in builtin_derivations("seed001") if p.name == "kim_eq6_8.toml")

    def compared():
        for memo in MEMOS:
            memo.forget()
        return ComparisonEngine(samples=60, param_sets=2, seed=SEED).compare(
            load_derivation(path))

    cold = compared()
    save_memos()
    assert [memo.path().is_file() for memo in MEMOS[:3]] == [True] * 3
    warm = compared()
    assert warm.records == cold.records
    assert warm.causes == cold.causes
    assert any(r.residual not in (None, "0") for r in cold.records)
    for memo in MEMOS:
        memo.forget()


def test_a_second_process_finds_every_form_the_first_remembered(tmp_path, monkeypatch):
    r"""Two processes with different hash seeds (as every two runs have) compare the same
    derivation: the second, which reads the closed forms the first derived back from disk,
    finds every printed form, compiled function and truth in the document's symbols the first
    remembered, so the memo files gain no entry. Keyed by the pickles of SymPy expressions
    (which record which parts are one object in memory: not the same for an expression read
    back), they did not (seed 001's Kim (6)-(8): the truth in its symbols was made again)."""
    import os
    import subprocess
    import sys

    from wheeled_dyn.compare.presentation.in_document import IN_DOCUMENT
    path = next(p for p in builtin_derivations("seed001") if p.name == "kim_eq6_8.toml")
    code = ("import sys\nfrom wheeled_dyn.compare.engine import ComparisonEngine\n"
            "from wheeled_dyn.derivations import load_derivation\n"
            "ComparisonEngine(samples=100, param_sets=2, seed=1).compare("
            "load_derivation(sys.argv[1]))\n")
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))    # load() checks with its key
    counts = []
    for seed in ("1", "2"):
        env = {**os.environ, CACHE_ENV: str(tmp_path / "cache"), "PYTHONHASHSEED": seed,
               "WHEELED_DYN_REUSE": "forms"}
        done = subprocess.run([sys.executable, "-c", code, str(path)], env=env,
                              capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, done.stderr[-2000:]
        files = sorted((tmp_path / "cache").rglob("*.pickle"))
        counts.append({f.name: len(load(f, dict) or {}) for f in files
                       if f.parent.name in ("compare", "compiled")})
    assert counts[0] == counts[1]
    assert any(name.startswith(IN_DOCUMENT.name) and n for name, n in counts[0].items())
    assert all(counts[0].values())


def test_keys_are_equal_exactly_for_equal_expressions():
    r"""A memo's key (:func:`wheeled_dyn.disk_cache.key_bytes`) is the same for expressions
    SymPy holds equal however they were built, and differs wherever SymPy's ``==`` does: a
    symbol's assumptions, a float's precision, an undefined function's assumptions, a
    rational for a float of the same value, the order of an unevaluated sum (``srepr``, the
    key before, printed ``f`` with and without ``real=True`` alike)."""
    from wheeled_dyn.disk_cache import key_bytes
    y = sp.Symbol("y")
    built = [(x + 2 * phi) * sp.sin(phi), sp.sin(phi) * (2 * phi + x),
             sp.sympify("sin(phi)*(x + 2*phi)", locals={"x": x, "phi": phi})]
    assert len({key_bytes(("A", e)) for e in built}) == 1
    f_real, f_plain = sp.Function("f", real=True), sp.Function("f")
    different = [x, sp.Symbol("x"), sp.Symbol("x", positive=True), sp.Float("1.5"),
                 sp.Float("1.5", 30), sp.Rational(3, 2), f_real(y), f_plain(y),
                 sp.Add(x, y, evaluate=False), sp.Add(y, x, evaluate=False), sp.pi, sp.E,
                 sp.Matrix([[x, y]]), sp.Matrix([[x], [y]]), sp.ImmutableMatrix([[x, y]])]
    for a in different:
        for b in different:
            assert (key_bytes(a) == key_bytes(b)) == (a is b or (a == b and type(a) is type(b)
                                                                 and getattr(a, "shape", 0)
                                                                 == getattr(b, "shape", 0))), (a, b)


def test_a_function_compiled_again_is_the_one_made_before():
    r"""Equal expressions give the same compiled function object in a process (made once);
    a different expression, or the same one with the arguments in another order, does not."""
    f = compiled.numpy_function([x, phi], x * sp.sin(phi) + 1)
    assert compiled.numpy_function([x, phi], sp.sin(phi) * x + 1) is f
    assert compiled.numpy_function([phi, x], x * sp.sin(phi) + 1) is not f
    assert compiled.numpy_function([x, phi], x * sp.cos(phi) + 1) is not f
    assert f(2.0, 0.5) == 2.0 * np.sin(0.5) + 1


def test_the_command_saves_its_memos_before_it_ends(tmp_path):
    r"""The command ends without the interpreter's shutdown (``cli.main._exit_now``): what it
    made is still on disk — its reports, the memos of the run (saved as it writes its
    reports, the exit handlers saving any left) — and the exit code is the command's (0,
    then 2 for a missing file, with one error line)."""
    import os
    import subprocess
    import sys
    path = next(p for p in builtin_derivations("seed001") if p.name.startswith("kim_eq1_3"))
    env = {**os.environ, CACHE_ENV: str(tmp_path / "cache"), "WHEELED_DYN_REUSE": "forms"}
    run = [sys.executable, "-m", "wheeled_dyn", "compare", "wip"]
    done = subprocess.run([*run, str(path), "--out", str(tmp_path / "out")], env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    assert (tmp_path / "out" / "report.json").is_file()
    saved = {f.parent.name: len(load(f, dict) or {})
             for f in (tmp_path / "cache").rglob("*.pickle") if f.parent.name != "results"}
    assert saved.get("compare") and saved.get("report"), saved
    missing = subprocess.run([*run, str(tmp_path / "none.toml")], env=env,
                             capture_output=True, text=True, timeout=600)
    assert missing.returncode == 2
    assert missing.stderr.strip().startswith("wheeled-dyn: error:"), missing.stderr
