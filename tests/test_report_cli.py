"""The report command and writers: three files, whole or nothing; errors name the place."""

from __future__ import annotations

import json


from wheeled_dyn.cli.main import main
from wheeled_dyn.derivations import builtin_derivations

#: A small grid keeps these tests fast; the engine's numbers are tested elsewhere.
SAMPLES, SETS = "40", "2"
EQ25 = next(p for p in builtin_derivations("seed001") if p.name == "eq25_lagrange.toml")


def test_compare_writes_three_reports(tmp_path, capsys):
    out = tmp_path / "r"
    assert main(["compare", "wip", str(EQ25), "--out", str(out), "--samples", SAMPLES,
                 "--param-sets", SETS]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == ["report.html", "report.json", "report.md"]
    data = json.loads((out / "report.json").read_text())
    records = {r["element"]: r for r in data["derivations"][0]["records"]}
    # seed 001's eq. (25): C[3,2] has phi-dot where psi-dot fits, A[2,1] has /R**2 for /R
    assert records["C[3,2]"]["verdict"] == "differs"
    assert any(d.startswith("swap: dphi where dpsi fits") for d in records["C[3,2]"]["diagnoses"])
    assert any(d.startswith("dimension") for d in records["A[2,1]"]["diagnoses"])
    assert records["h[1]:dpsi*dpsi"]["verdict"] == "differs"          # the missing psi-dot**2
    html = (out / "report.html").read_text()
    assert "<math" in html and "http://" not in html.replace("http://www.w3.org/1998/Math/MathML", "")
    # the CLI prints the causes one line each: the diagnosis, then the elements it explains
    assert "dphi where dpsi fits — C[3,2]" in capsys.readouterr().out


def test_malformed_file_writes_nothing(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(EQ25.read_text().replace('title = "', 'title = = "', 1))
    out = tmp_path / "r"
    assert main(["compare", "wip", str(EQ25), str(bad), "--out", str(out),
                 "--samples", SAMPLES, "--param-sets", SETS]) == 2
    err = capsys.readouterr().err
    assert "bad.toml:" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_file_for_another_model_is_refused(tmp_path, capsys):
    assert main(["compare", "tiago", str(EQ25), "--out", str(tmp_path / "r"),
                 "--samples", SAMPLES, "--param-sets", SETS]) == 2
    assert "'wip'" in capsys.readouterr().err


def test_unwritable_folder_is_one_error(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["compare", "wip", str(EQ25), "--out", str(blocker / "sub"),
                 "--samples", SAMPLES, "--param-sets", SETS]) == 2
    err = capsys.readouterr().err
    assert str(blocker) in err and "expected a folder" in err and len(err.splitlines()) == 1
