"""Bad input gets one clear error of the project's own type, naming the place."""

from __future__ import annotations

from pathlib import Path

import pytest

from wheeled_dyn import WipParameters, builtin_coordinate_set, load_model, matrices
from wheeled_dyn.cli.main import main
from wheeled_dyn.errors import (InputFileError, ModelError, ParameterError, StateError,
                                UnknownNameError, WheeledDynError)
from wheeled_dyn.models import ModelSpec, build_wheeled_model
from wheeled_dyn.paths import urdf_dir

WIP_URDF = urdf_dir() / "wip.urdf"


def _spec(path: Path, **changes) -> ModelSpec:
    base = dict(name="test", urdf=path, body="body", wheels=("wheel_left", "wheel_right"),
                up=(0.0, 1.0, 0.0))
    return ModelSpec(**{**base, **changes})


def test_missing_file(tmp_path):
    with pytest.raises(InputFileError) as err:
        build_wheeled_model(_spec(tmp_path / "nope.urdf"))
    assert "nope.urdf" in str(err.value) and "no such" in str(err.value)


def test_malformed_urdf_names_line_and_column(tmp_path):
    bad = tmp_path / "bad.urdf"
    lines = WIP_URDF.read_text().splitlines()
    lines[30] = lines[30] + "<unclosed"
    bad.write_text("\n".join(lines))
    with pytest.raises(InputFileError) as err:
        build_wheeled_model(_spec(bad))
    assert err.value.line is not None and err.value.path == bad
    assert f"bad.urdf:{err.value.line}" in str(err.value)


def test_unknown_wheel_and_body_list_valid_names():
    with pytest.raises(UnknownNameError) as err:
        build_wheeled_model(_spec(WIP_URDF, wheels=("wheel_left", "wheel_middle")))
    assert err.value.name == "wheel_middle" and "wheel_right" in err.value.valid
    with pytest.raises(UnknownNameError) as err:
        build_wheeled_model(_spec(WIP_URDF, body="torso"))
    assert "body" in err.value.valid and "torso" in str(err.value)


def test_wheel_without_radius(tmp_path):
    text = WIP_URDF.read_text()
    start = text.index('<link name="wheel_left">')
    end = text.index("</link>", start)
    block = text[start:end]
    stripped = block.replace(block[block.index("<visual>"):block.rindex("</collision>") + 12], "")
    path = tmp_path / "noradius.urdf"
    path.write_text(text[:start] + stripped + text[end:])
    with pytest.raises(ModelError) as err:
        build_wheeled_model(_spec(path))
    assert err.value.item == "wheel_left" and "radius" in str(err.value)
    # given explicitly, it builds
    assert build_wheeled_model(_spec(path, radius=0.25)).wheels[0].radius == 0.25


@pytest.mark.parametrize("changes,name", [({"m_S": -1.0}, "m_S"), ({"R": 0.0}, "R"),
                                          ({"I1": 10.0, "I2": 1.0, "I3": 1.0}, "body"),
                                          ({"Iw3": 1.0, "Iw2": 0.1}, "wheel"),
                                          ({"d": float("nan")}, "d")])
def test_non_physical_parameters(changes, name):
    with pytest.raises(ParameterError) as err:
        WipParameters(**changes)
    assert name in str(err.value)


def test_nan_in_state_is_named():
    with pytest.raises(StateError) as err:
        matrices("wip", phi=float("nan"))
    assert err.value.name == "phi"


def test_unknown_coordinate_set_and_model():
    with pytest.raises(UnknownNameError) as err:
        builtin_coordinate_set(load_model("wip"), "polar")
    assert "seed001" in err.value.valid
    with pytest.raises(UnknownNameError) as err:
        load_model("segway")
    assert "wip" in err.value.valid


def test_cli_reports_errors_in_one_line(capsys):
    assert main(["matrices", "wip", "--coords", "polar"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "polar" in err[0] and "seed001" in err[0]


def test_every_error_is_a_wheeled_dyn_error():
    for cls in (InputFileError, ModelError, ParameterError, StateError, UnknownNameError):
        assert issubclass(cls, WheeledDynError)
