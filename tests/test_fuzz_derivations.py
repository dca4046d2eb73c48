"""Random mutations of the shipped derivation files, through the ``compare`` command: never a
traceback, never a hang, never a verdict computed on values that are not finite.

Each mutation (Hypothesis, derandomized: the same examples every run) cuts, duplicates or
inserts text in a shipped file — brackets, quotes, operators, huge powers, ``nan``, ``inf``,
unknown names, stray table headers. The command must either compare (exit 0, a report whose
"agrees" verdicts all have a finite error) or refuse with one line ``wheeled-dyn: error: ...``
(exit 2), within :data:`EXAMPLE_SECONDS`.
"""

from __future__ import annotations

import json
import math
import signal
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis", reason="property tests need hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from wheeled_dyn.cli.main import main  # noqa: E402
from wheeled_dyn.derivations import builtin_derivations  # noqa: E402

#: Examples per run, and the longest one example may take (a hang fails the test).
MAX_EXAMPLES = 60
EXAMPLE_SECONDS = 60
#: The comparison grid of each example (small: the verdicts' honesty, not statistics).
SAMPLES, PARAM_SETS = "6", "1"

#: Shipped files mutated (small and quick ones of each group).
FILES = {p.name: p for g in ("seed001", "seed000", "seed002") for p in builtin_derivations(g)
         if p.name in {"kim_eq1_3.toml", "eq25_lagrange.toml", "p4_4_rod_pendulum.toml",
                       "p4_8_rolling_disk.toml", "s3_3_sphere_plane.toml"}}
#: Pieces a mutation inserts.
PIECES = ["(", ")", "[", "]", "\"", "'", "=", ",", "*", "**", "/", "+", "-", "\n", "#",
          "nan", "inf", "1e400", "0", "9**9**9", "**2000", "sin(", "x_unknown", "M(nolink)",
          "[matrices]", "[[step]]", "{", "}", "\\", "\u00e9", "\t", "1/0", "zoo", "dphi"]


@st.composite
def mutations(draw) -> tuple[str, str]:
    name = draw(st.sampled_from(sorted(FILES)))
    text = FILES[name].read_text()
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(text)))
        kind = draw(st.sampled_from(["insert", "cut", "duplicate"]))
        if kind == "insert":
            text = text[:i] + draw(st.sampled_from(PIECES)) + text[i:]
        else:
            j = min(len(text), i + draw(st.integers(1, 40)))
            text = text[:i] + (text[i:j] * 2 if kind == "duplicate" else "") + text[j:]
    return name, text


class _Hang(Exception):
    pass


def _alarm(signum, frame):
    raise _Hang(f"an example ran longer than {EXAMPLE_SECONDS} s")


@settings(max_examples=MAX_EXAMPLES, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(mutation=mutations())
def test_mutated_file_is_compared_or_refused_in_one_line(mutation, tmp_path_factory, capsys):
    name, text = mutation
    folder = tmp_path_factory.mktemp("fuzz")
    path = folder / name
    path.write_text(text)
    # the file's model: the shipped file's (a mutation may break the model line itself)
    model = next(line.split("=", 1)[1].strip().strip('"') for line in
                 FILES[name].read_text().splitlines() if line.startswith("model"))
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(EXAMPLE_SECONDS)
    try:
        code = main(["compare", model, str(path), "--out", str(folder / "out"),
                     "--samples", SAMPLES, "--param-sets", PARAM_SETS])
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    err = capsys.readouterr().err
    assert code in (0, 2), (code, err)
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("wheeled-dyn: error: "), err
        assert "Traceback" not in err
        return
    report = json.loads((folder / "out" / "report.json").read_text())
    for d in report["derivations"]:
        for r in d["records"]:
            if r["verdict"] == "agrees" and r.get("max_error") is not None:
                assert math.isfinite(r["max_error"]), (r["element"], r["max_error"])
    assert not list(Path(folder / "out").glob(".*"))       # no temporary file left
