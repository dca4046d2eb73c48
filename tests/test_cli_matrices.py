"""``wheeled-dyn matrices``: the CLI prints what the Python API computes."""

from __future__ import annotations

import json

import numpy as np

from wheeled_dyn import matrices
from wheeled_dyn.cli.main import main

#: Tolerance of a JSON round trip of floats.
JSON_TOL = 1e-12


def test_json_matches_api(capsys):
    assert main(["matrices", "wip", "--json", "--state", "phi=0.2,dx=1,dpsi=0.5,dphi=-0.3"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["coordinates"] == ["dx", "dpsi", "dphi"]
    terms = matrices("wip", phi=0.2, dx=1.0, dpsi=0.5, dphi=-0.3)
    for key in ("A", "C", "Q", "B", "h"):
        assert np.allclose(out[key], getattr(terms, key), atol=JSON_TOL), key


def test_param_override_changes_the_mass_entry(capsys):
    assert main(["matrices", "wip", "--json", "--param", "m_S=50,m_C=2,Iw3=0.1,R=0.2"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(out["A"][0][0] - (50 + 2 * 2 + 2 * 0.1 / 0.2**2)) < JSON_TOL


def test_table_lists_every_coordinate(capsys):
    assert main(["matrices", "wip", "--coords", "wheels"]) == 0
    out = capsys.readouterr().out
    for name in ("dtheta_l", "dtheta_r", "dphi", "tau_l", "tau_r"):
        assert name in out
