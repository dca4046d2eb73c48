"""README.md as a newcomer reads it: short, and every command in it runs as printed.

- Every ``./wd ...`` command it prints (in a shell block or in backticks) runs, in the order
  printed, in a scratch copy of the repository's files, and exits 0. One is run in a form that
  can run here, for a stated reason (:data:`RUN_AS`).
- Every synopsis of the command table (``./wd compare MODEL FILE... [--watch]``) names a
  sub-command and options that exist.
- The Python API example runs as printed (in a scratch folder: it writes an HTML animation),
  and what it claims in its comments holds.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
#: The README's length a newcomer reads in five minutes (lines).
MAX_LINES = 200
#: Seconds one command may take (the default report recomputed on a loaded 2-core machine
#: took 12 s; the first one, closed forms derived, 23 s).
COMMAND_TIMEOUT = 600
#: Commands that cannot run here as printed, the form they are run in, and why.
RUN_AS = {
    "./wd test": ("./wd test --collect-only -q tests/test_readme.py",
                  "the suite inside its own test: collected, not run"),
}
#: Placeholders of a synopsis (the command table), not a command to run.
SYNOPSIS = re.compile(r"\[|\.\.\.|\b(MODEL|FILE|URDF|NAME|S)\b|k=v")


def _text() -> str:
    return README.read_text(encoding="utf-8")


def _python_blocks() -> list[str]:
    return re.findall(r"```python\n(.*?)```", _text(), re.DOTALL)


def _printed_commands() -> list[str]:
    r"""Every ``./wd <sub-command>`` of the README, each once, in the order printed: the lines
    of its shell blocks (fences without a language) and the spans in backticks elsewhere."""
    found: list[str] = []
    fence: str | None = None                  # the language of the open fence, "" for shell
    for line in _text().splitlines():
        if line.startswith("```"):
            fence = line[3:].strip() if fence is None else None
        elif fence == "" and line.startswith("./wd "):
            found.append(line.split("#")[0].strip())
        elif fence is None:
            found += [c.replace("\\|", "|").strip() for c in re.findall(r"`(\./wd [^`]*)`", line)]
    return list(dict.fromkeys(found))


def test_readme_is_short():
    lines = _text().count("\n")
    assert lines <= MAX_LINES, f"README.md has {lines} lines"


def test_the_quick_start_has_the_two_commands_and_their_durations():
    quick = _text().split("## Quick start", 1)[1].split("\n## ", 1)[0]
    assert "```\n./wd report\n./wd test\n```" in quick
    for command in ("./wd report", "./wd test"):
        (row,) = [line for line in quick.splitlines() if line.startswith(f"| `{command}` |")]
        first, later = row.split("|")[2:4]
        assert re.search(r"\d+ (s|min)", first) and re.search(r"\d+ (s|min)", later), row


def test_every_synopsis_names_options_that_exist():
    from wheeled_dyn.cli.main import build_parser
    parser = build_parser()
    subcommands = parser._subparsers._group_actions[0].choices      # argparse's own table
    synopses = [c for c in _printed_commands() if SYNOPSIS.search(c)]
    assert len(synopses) >= 7
    for synopsis in synopses:
        words = synopsis.split()
        sub = subcommands[words[1]]
        options = {o for a in sub._actions for o in a.option_strings}
        for option in re.findall(r"(?<![\w-])--[a-z][a-z-]*", synopsis):
            assert option in options, (synopsis, option)


def _scratch_copy(tmp_path: Path) -> Path:
    r"""The repository's tracked files in ``tmp_path``, with its ``.venv`` linked (``./wd``
    finds its environment there and installs nothing)."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True,
                           check=True).stdout.decode().split("\0")
    copy = tmp_path / "repo"
    for name in filter(None, files):
        if (ROOT / name).is_file():
            (copy / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, copy / name)
    (copy / ".venv").symlink_to(ROOT / ".venv")
    return copy


@pytest.mark.slow
@pytest.mark.skipif(not (ROOT / ".venv" / "bin" / "wheeled-dyn").exists(),
                    reason="no .venv with wheeled-dyn in the repository (run ./wd list once)")
def test_every_command_in_the_readme_runs_as_printed(tmp_path):
    commands = [c for c in _printed_commands() if not SYNOPSIS.search(c)]
    assert {"./wd report", "./wd test", "./wd compare wip examples/my_planar_robot.toml"} \
        <= set(commands)
    copy = _scratch_copy(tmp_path)
    env = {**os.environ, "WHEELED_DYN_REUSE": "0"}
    for command in commands:
        run, _why = RUN_AS.get(command, (command, ""))
        done = subprocess.run(run, shell=True, check=False, cwd=copy, env=env, capture_output=True,
                              text=True, timeout=COMMAND_TIMEOUT)
        assert done.returncode == 0, (command, run, done.stdout[-2000:], done.stderr[-2000:])
        assert not done.stderr.startswith("wd: creating"), "the scratch copy installed again"
    assert (copy / "reports" / "report.html").is_file()
    assert (copy / "my_robot.toml").is_file()


@pytest.mark.slow
def test_readme_python_example_runs(tmp_path, monkeypatch):
    (block,) = _python_blocks()
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    exec(compile(block, str(README), "exec"), namespace)   # noqa: S102 (the README's own code)
    assert (tmp_path / "fall.html").is_file()
    assert namespace["result"].form == "matrices"           # the last: the rod from SymPy
    assert all(r.verdict == "agrees" for r in namespace["result"].records)
    from wheeled_dyn.symbolic import true_expressions
    cs = namespace["cs"]
    assert str(true_expressions("wip", cs)["h[1]:dpsi*dpsi"]) == \
        "d*m_S*sin(phi) - d_x*m_S*cos(phi)"                  # as its comment says


def test_every_file_the_readme_names_exists():
    text = _text()
    linked = re.findall(r"\]\((?!https?:)([^)#]+)\)", text)
    named = re.findall(r"`((?:docs|tests|examples|notebooks|src|urdf|benchmarks)/[^`<>* ]+)`", text)
    assert len(linked) >= 8
    missing = [p for p in {*linked, *named} if not (ROOT / p).exists()]
    assert not missing, missing
