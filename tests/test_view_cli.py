"""``wheeled-dyn view``: an exported animation is one self-contained file; bad names are one error."""

from __future__ import annotations

from wheeled_dyn.cli.main import main


def test_export_writes_one_offline_file(tmp_path, capsys):
    out = tmp_path / "anim.html"
    assert main(["view", "wip", "--scenario", "fall", "--duration", "0.5", "--export", str(out)]) == 0
    text = out.read_text()
    assert "<html" in text.lower() and "animation" in text.lower()
    assert 'src="http' not in text and "src='http" not in text       # nothing fetched
    assert str(out) in capsys.readouterr().out


def test_unknown_scenario_lists_the_model_s_ones(capsys):
    assert main(["view", "wip", "--scenario", "circle", "--export", "x.html"]) == 2
    err = capsys.readouterr().err
    assert "circle" in err and "balance" in err and "fall" in err
