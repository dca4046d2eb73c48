"""Bad options, bad output places, bad input files: one line on stderr naming the place, exit
code 2, checked before any computing; Ctrl-C: exit 130, no traceback, nothing left behind;
errors and crashes of the report's worker processes reach the user as one line."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from wheeled_dyn.cli.main import main
from wheeled_dyn.derivations import builtin_derivations

SEED001 = {p.name: p for p in builtin_derivations("seed001")}
KIM = SEED001["kim_eq1_3.toml"]
ROD = {p.name: p for p in builtin_derivations("seed000")}["p4_4_rod_pendulum.toml"]
LONG_NAME = "a" * 300
#: Seconds a subprocess test may take at most (a hang fails instead of blocking the suite).
SUBPROCESS_TIMEOUT = 240


def _one_error_line(capsys) -> str:
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("wheeled-dyn: error: ") and "Traceback" not in captured.err
    return lines[0]


@pytest.fixture
def no_computing(monkeypatch):
    r"""Any comparison or simulation started fails the test: errors must come before."""
    from wheeled_dyn.compare import engine
    from wheeled_dyn.simulate import documented, scenarios

    def forbidden(*args, **kwargs):
        raise AssertionError("computing started before the arguments were checked")
    monkeypatch.setattr(engine.ComparisonEngine, "compare", forbidden)
    monkeypatch.setattr(documented, "side_by_side", forbidden)
    monkeypatch.setattr(scenarios, "run_scenario", forbidden)


def _mutated(tmp_path: Path, source: Path, old: str, new: str, name: str | None = None) -> Path:
    text = source.read_text()
    assert old in text, old
    path = tmp_path / (name or source.name)
    path.write_text(text.replace(old, new, 1))
    return path


# -- numeric options --------------------------------------------------------------------------
@pytest.mark.parametrize("options,named", [
    (["--samples", "0"], "--samples"), (["--samples", "-1"], "--samples"),
    (["--param-sets", "0"], "--param-sets"), (["--samples", str(10 ** 9)], "--samples"),
    (["--samples", "100000", "--param-sets", "100"], "--samples × --param-sets")])
def test_sample_grid_out_of_range(options, named, tmp_path, capsys, no_computing):
    out = tmp_path / "out"
    assert main(["compare", "wip", str(KIM), "--out", str(out), *options]) == 2
    line = _one_error_line(capsys)
    assert named in line and "expected" in line
    assert main(["report", "--out", str(out), *options]) == 2
    assert named in _one_error_line(capsys)
    assert not out.exists()


@pytest.mark.parametrize("duration", ["0", "-3", "nan", "1e6", "inf"])
def test_durations_out_of_range(duration, tmp_path, capsys, no_computing):
    assert main(["view", "wip", "--duration", duration, "--export",
                 str(tmp_path / "a.html")]) == 2
    line = _one_error_line(capsys)
    assert "--duration" in line and "at most 60" in line
    assert main(["simulate", str(KIM), "--duration", duration, "--out", str(tmp_path)]) == 2
    assert "--duration" in _one_error_line(capsys)
    assert not (tmp_path / "a.html").exists()


def test_huge_starting_rate_is_a_stated_limit(tmp_path, capsys, no_computing):
    assert main(["simulate", str(KIM), "--state", "dpsi=1e6", "--out", str(tmp_path)]) == 2
    line = _one_error_line(capsys)
    assert "dpsi" in line and "at most 100" in line


@pytest.mark.parametrize("command", ["simulate", "matrices"])
def test_state_key_given_twice(command, tmp_path, capsys, no_computing):
    args = ([command, str(KIM), "--out", str(tmp_path)] if command == "simulate"
            else [command, "wip"])
    assert main([*args, "--state", "phi=0.1,phi=0.2"]) == 2
    line = _one_error_line(capsys)
    assert "phi" in line and "twice" in line


@pytest.mark.parametrize("value", ["nan", "inf", "1e999"])
def test_state_not_finite(value, capsys):
    assert main(["matrices", "wip", "--state", f"phi={value}"]) == 2
    assert "phi" in _one_error_line(capsys)


@pytest.mark.parametrize("value", ["1_0", "0x10", "1e1_0"])
def test_state_not_a_decimal_number(value, capsys):
    r"""Python's ``float`` reads ``1_0`` as ten: a typo for 1.0 (or 10) taken silently; the
    value is a decimal number as a URDF writes it, or one error naming it."""
    assert main(["matrices", "wip", "--state", f"phi={value}"]) == 2
    line = _one_error_line(capsys)
    assert "phi" in line and "decimal number" in line, line


@pytest.mark.parametrize("value", ["inf", "1_0"])
def test_a_parameter_that_is_no_number_is_named_a_parameter(value, capsys):
    r"""``--param m_S=inf``: one error naming the parameter as a parameter (it said "state
    entry m_S")."""
    assert main(["matrices", "wip", "--param", f"m_S={value}"]) == 2
    line = _one_error_line(capsys)
    assert "parameter m_S" in line and "state entry" not in line, line


# -- output places ----------------------------------------------------------------------------
def test_out_that_is_a_file(tmp_path, capsys, no_computing):
    target = tmp_path / "taken"
    target.write_text("keep me")
    for command in (["simulate", str(KIM)], ["compare", "wip", str(KIM)], ["report"]):
        assert main([*command, "--out", str(target)]) == 2
        line = _one_error_line(capsys)
        assert str(target) in line and "expected a folder" in line
    assert target.read_text() == "keep me"


@pytest.mark.parametrize("command", [["compare", "wip", str(KIM)], ["simulate", str(KIM)]])
def test_name_of_300_characters(command, tmp_path, capsys, no_computing):
    assert main([*command, "--out", str(tmp_path / LONG_NAME)]) == 2
    assert "at most 255 bytes" in _one_error_line(capsys)


@pytest.mark.parametrize("export,expected", [
    ("{tmp}", "is a folder"), ("{tmp}/" + LONG_NAME + ".html", "at most 255 bytes"),
    ("{tmp}/file.txt/anim.html", "is a file"), ("{tmp}/anim.txt", "ending in .html")])
def test_export_places(export, expected, tmp_path, capsys, no_computing):
    (tmp_path / "file.txt").write_text("")
    assert main(["view", "wip", "--export", export.format(tmp=tmp_path)]) == 2
    assert expected in _one_error_line(capsys)


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux /proc (read-only)")
def test_export_to_a_read_only_place(capsys, no_computing):
    assert main(["view", "wip", "--export", "/proc/anim.html"]) == 2
    assert "cannot write in /proc" in _one_error_line(capsys)


def test_export_on_a_full_disk_leaves_nothing(tmp_path, capsys, monkeypatch):
    import wheeled_dyn.output as output

    def full(*args):
        raise OSError(28, "No space left on device", args[0])
    monkeypatch.setattr(output.os, "replace", full)
    target = tmp_path / "anim.html"
    assert main(["view", "wip", "--scenario", "fall", "--duration", "0.2",
                 "--export", str(target)]) == 2
    assert "No space left on device" in _one_error_line(capsys)
    assert list(tmp_path.iterdir()) == []


# -- input files ------------------------------------------------------------------------------
@pytest.mark.parametrize("command", ["compare", "simulate"])
def test_empty_folder_as_input(command, tmp_path, capsys, no_computing):
    empty = tmp_path / "empty"
    empty.mkdir()
    args = ["compare", "wip"] if command == "compare" else ["simulate"]
    assert main([*args, str(empty), "--out", str(tmp_path / "out")]) == 2
    assert "folder without derivation files" in _one_error_line(capsys)
    assert not (tmp_path / "out").exists()


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")
def test_fifo_and_device_as_derivation_file(tmp_path, capsys, no_computing):
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    assert main(["compare", "wip", str(fifo), "--out", str(tmp_path / "out")]) == 2
    assert "is a FIFO, not a regular file" in _one_error_line(capsys)
    if Path("/dev/zero").exists():
        assert main(["compare", "wip", "/dev/zero", "--out", str(tmp_path / "out")]) == 2
        assert "is a device" in _one_error_line(capsys)


def test_input_key_that_is_not_a_model_input(tmp_path, capsys, no_computing):
    path = _mutated(tmp_path, KIM, 'tau_r = "beta3"\n', 'tau_r = "beta3"\ntau_x = "beta3"\n')
    line_no = path.read_text().splitlines().index('tau_x = "beta3"') + 1
    assert main(["compare", "wip", str(path), "--out", str(tmp_path / "out")]) == 2
    line = _one_error_line(capsys)
    assert f"{path}:{line_no}: inputs.tau_x" in line and "tau_l, tau_r" in line


def test_unknown_link_names_file_line_and_item(tmp_path, capsys, no_computing):
    path = _mutated(tmp_path, KIM, 'value = "m_S"', 'value = "M(bodyy)"')
    line_no = next(i for i, t in enumerate(path.read_text().splitlines(), 1) if "bodyy" in t)
    assert main(["compare", "wip", str(path), "--out", str(tmp_path / "out")]) == 2
    line = _one_error_line(capsys)
    assert f"{path}:{line_no}: symbols.m_s.value" in line and "'bodyy'" in line
    assert "body, wheel_left, wheel_right" in line


def test_holonomic_file_without_rolling_reads_none(tmp_path):
    from wheeled_dyn.derivations import load_derivation
    path = _mutated(tmp_path, ROD, 'rolling = "none"\n', "")
    assert load_derivation(path).coordinates.rolling == "none"


def test_holonomic_file_eliminating_rolling_gets_the_right_advice(tmp_path, capsys,
                                                                 no_computing):
    path = _mutated(tmp_path, ROD, 'rolling = "none"\n', 'rolling = "eliminate"\n')
    assert main(["compare", "rod_pendulum", str(path), "--out", str(tmp_path / "out")]) == 2
    line = _one_error_line(capsys)
    assert "coordinates.rolling" in line and 'rolling = "none"' in line


@pytest.mark.parametrize("element,reason", [
    ("(1+sin(phi))**(10**10**10)*ddx", "exponent"), ("9**9**9**9*ddx", "exponent"),
    ("(" + "+".join(["m_c"] * 20000) + ")*ddx", "too long"),
    ("(1+sin(phi))**2000*ddx", "exponent 2000")])
def test_expression_limits_through_the_command(element, reason, tmp_path, capsys,
                                               no_computing):
    path = _mutated(tmp_path, KIM, "3*(m_c + m_s)*ddx", element)
    assert main(["compare", "wip", str(path), "--out", str(tmp_path / "out")]) == 2
    line = _one_error_line(capsys)
    assert f"{path}:" in line and "equation 1" in line and reason in line


# -- simulate: honest energy figures ----------------------------------------------------------
def test_energy_deviation_is_the_largest_over_the_run():
    from wheeled_dyn.cli.simulate_cmd import energy_deviation
    assert energy_deviation(np.array([1.0, 3.0, -2.0, 1.0])) == 3.0
    assert np.isnan(energy_deviation(np.array([1.0, np.inf])))


def test_simulate_prints_what_the_plot_shows(tmp_path, capsys):
    from wheeled_dyn.derivations import load_derivation
    from wheeled_dyn.cli.simulate_cmd import default_start
    from wheeled_dyn.simulate.documented import side_by_side
    assert main(["simulate", str(KIM), "--duration", "2", "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    d = load_derivation(KIM)
    s = side_by_side(d, default_start(d), 2.0)
    plotted = s.document.energy - s.document.energy[0]          # what plots.py draws
    assert f"document {np.abs(plotted).max():.3g} J" in printed
    assert (tmp_path / "kim_eq1_3_simulation.png").read_bytes()[:4] == b"\x89PNG"



def test_the_default_start_keeps_a_position_in_the_range_the_file_draws_it(tmp_path):
    r"""The rolling disk of ``data/published`` draws its lean in [0.3, 2.84] (flat on the
    ground at 0): its simulation starts there, at the range's middle; it started at 0, where
    the document's equations are singular ("not simulated ... lying flat")."""
    from pathlib import Path

    from wheeled_dyn.cli.simulate_cmd import default_start
    from wheeled_dyn.derivations import load_derivation
    d = load_derivation(Path(__file__).parent / "data" / "published" /
                        "rolling_disk_multipliers.toml")
    start = default_start(d)
    assert start["theta"] == pytest.approx(0.5 * (0.3 + 2.84))
    assert start["psi"] == 0.2 and "x" not in start      # the others as before

# -- worker processes and Ctrl-C --------------------------------------------------------------
def _run(script: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(script), *args],
                          capture_output=True, text=True, timeout=SUBPROCESS_TIMEOUT)


def test_report_with_a_model_urdf_missing(tmp_path):
    done = _run("""
        import sys, wheeled_dyn.models.urdf_packages as packages
        from pathlib import Path
        packages.urdf_dir = lambda: Path(sys.argv[1])
        from wheeled_dyn.cli.main import main
        sys.exit(main(["report", "--samples", "20", "--param-sets", "1", "--out", sys.argv[2]]))
        """, str(tmp_path), str(tmp_path / "out"))
    assert done.returncode == 2, done.stderr
    line = done.stderr.strip()
    assert len(line.splitlines()) == 1 and line.startswith("wheeled-dyn: error: "), line
    assert "wip.toml" in line and "'wip.urdf'" in line and str(tmp_path) in line, line
    assert not (tmp_path / "out").exists()


_IN_WORKER = """
    import os, signal, sys
    import wheeled_dyn.compare.engine as engine
    from wheeled_dyn.errors import DerivationError
    original = engine.ComparisonEngine.compare
    def compare(self, d):
        if d.path.name == "kim_eq6_8.toml":
            if sys.argv[1] == "error":
                raise DerivationError(d.path, "A[1,1]", "planted", line=7)
            os.kill(os.getpid(), signal.SIGSEGV)
        return original(self, d)
    engine.ComparisonEngine.compare = compare
    from wheeled_dyn.cli.main import main
    sys.exit(main(["report", "--samples", "20", "--param-sets", "1", "--out", sys.argv[2]]))
    """


@pytest.mark.skipif(sys.platform == "win32", reason="the pool forks its workers")
def test_error_in_a_worker_is_the_same_one_line(tmp_path):
    done = _run(_IN_WORKER, "error", str(tmp_path / "out"))
    assert done.returncode == 2, done.stderr
    assert done.stderr.strip() == f"wheeled-dyn: error: {SEED001['kim_eq6_8.toml']}:7: A[1,1]: planted"
    assert not (tmp_path / "out").exists()


@pytest.mark.skipif(sys.platform == "win32", reason="the pool forks its workers")
def test_crashed_worker_is_an_error_not_a_hang(tmp_path):
    done = _run(_IN_WORKER, "crash", str(tmp_path / "out"))
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "ended abruptly" in lines[0] and "kim_eq6_8.toml" in lines[0]


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_during_report(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "report.md").write_text("previous")
    proc = subprocess.Popen([sys.executable, "-m", "wheeled_dyn.cli.main", "report", "--samples",
                             "4000", "--param-sets", "5", "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    # imports done (about 0.5 s), workers comparing: the default report ends in about 2.5 s
    # here, this one (4000 states per set) in about 4.3 s
    time.sleep(2.5)
    os.killpg(proc.pid, signal.SIGINT)    # as a terminal's Ctrl-C: the whole process group
    _, err = proc.communicate(timeout=SUBPROCESS_TIMEOUT)
    assert proc.returncode == 130, err
    assert err.strip() == "wheeled-dyn: interrupted"
    assert sorted(p.name for p in out.iterdir()) == ["report.md"]
    assert (out / "report.md").read_text() == "previous"


@pytest.mark.parametrize("module", ["wheeled_dyn", "wheeled_dyn.cli"])
def test_python_dash_m_runs_the_command(module):
    r"""``python -m wheeled_dyn`` (and ``.cli``) is the ``wheeled-dyn`` command: the same list
    of models, and a bad sub-command is one usage error with exit code 2."""
    ok = subprocess.run([sys.executable, "-m", module, "list"], capture_output=True, text=True,
                        timeout=120)
    assert ok.returncode == 0 and "wip" in ok.stdout, ok.stderr
    bad = subprocess.run([sys.executable, "-m", module, "nope"], capture_output=True, text=True,
                         timeout=120)
    assert bad.returncode == 2 and "invalid choice: 'nope'" in bad.stderr
    assert "Traceback" not in bad.stderr


def test_a_model_path_that_does_not_exist_is_said_so(tmp_path, capsys, monkeypatch):
    r"""``compare robots/dd.toml doc.toml`` from another folder: the path is taken from the
    working folder, where it does not exist; the error said only that the file describes
    another model."""
    from pathlib import Path
    data = Path(__file__).parent / "data" / "published"
    for name in ("dd_robot.toml", "dd_robot.urdf", "dd_multipliers.toml"):
        (tmp_path / name).write_text((data / name).read_text())
    monkeypatch.chdir(tmp_path.parent)
    assert main(["compare", "robots/dd_robot.toml", str(tmp_path / "dd_multipliers.toml"),
                 "--out", str(tmp_path / "out")]) == 2
    line = _one_error_line(capsys)
    assert "robots/dd_robot.toml does not exist" in line and str(tmp_path.parent) in line, line


def test_matrices_of_numbers_too_far_apart_say_their_entries_may_be_round_off(capsys):
    r"""``--param d=1e10`` (a body 1e10 m tall): A's small entries are round-off
    (A[dx,dpsi] = -21316 where 0 is exact), printed without a word; a note says so. The
    shipped numbers print none."""
    assert main(["matrices", "wip", "--param", "d=1e10", "--state", "phi=0.3"]) == 0
    assert "condition number" in capsys.readouterr().out
    assert main(["matrices", "wip", "--state", "phi=0.3"]) == 0
    assert "condition number" not in capsys.readouterr().out


@pytest.mark.parametrize("old, new, said", [
    ('model = "rod_pendulum"', 'model = "nosuch"', ":2: model: unknown model 'nosuch'"),
    ('configuration = { theta = "theta" }', 'configuration = { nosuch = "theta" }',
     ":5: coordinates.configuration.nosuch: unknown model coordinate 'nosuch'; valid: theta")])
def test_a_derivations_unknown_model_names_its_file_and_line(tmp_path, capsys, old, new, said):
    r"""A derivation naming a model, or a model coordinate, that does not exist: the error
    names the file, the line and the key (the model's named neither file nor line; the
    coordinate's glued the path to "configuration", with no line)."""
    text = ('title = "rod"\nmodel = "rod_pendulum"\n[coordinates]\npositions = ["theta"]\n'
            'configuration = { theta = "theta" }\n[symbols]\nm = "M(rod)"\nl = "length(rod)"\n'
            'g = "g"\n[matrices]\nA = "[[m*l**2/3]]"\nQ = "[m*g*l/2*sin(theta)]"\n')
    assert old in text
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, new))
    assert main(["compare", "rod_pendulum", str(path), "--out", str(tmp_path / "out")]) == 2
    line = _one_error_line(capsys)
    assert f"doc.toml{said}" in line, line


def test_list_reads_the_model_files_without_sympy_or_pinocchio():
    r"""``wheeled-dyn list`` reads every model file (its tables checked) and imports neither
    SymPy nor Pinocchio (the bench's target is 0.3 s; a check of ``[base] type`` that imported
    the model's module took it to 0.35 s). Counted by the modules loaded, not by a clock."""
    code = ("import sys; from wheeled_dyn.cli.main import main; main(['list']); "
            "print(sorted(m for m in ('sympy', 'pinocchio') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip().splitlines()[-1]
    assert out == "[]", out


def test_compare_of_a_shipped_derivation_imports_no_scipy(tmp_path):
    r"""``wheeled-dyn compare wip eq25_lagrange.toml`` needs no SciPy: its linear algebra took
    0.25–0.35 s to import (a quarter of the command's time, the bench's target being 1 s) for
    one pseudo-inverse by LAPACK's Cholesky solver. Counted by the modules loaded."""
    eq25 = next(p for p in builtin_derivations("seed001") if p.name == "eq25_lagrange.toml")
    code = ("import sys; from wheeled_dyn.cli.main import main; "
            f"main(['compare', 'wip', {str(eq25)!r}, '--out', {str(tmp_path)!r}]); "
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'scipy'))")
    env = {**os.environ, "WHEELED_DYN_REUSE": "forms"}       # compared, not read back
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env=env).stdout.strip().splitlines()[-1]
    assert out == "[]", out
