r"""The outline of a URDF (links, joints, cylinders) read with yourdfpy is kept in the disk
cache: a second read of the same text gives the same outline without importing yourdfpy; an
unreadable entry is read again from the file; a file yourdfpy rejects is never cached."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from wheeled_dyn.disk_cache import CACHE_ENV
from wheeled_dyn.errors import InputFileError
from wheeled_dyn.models.urdf_source import read_urdf

URDF = Path(__file__).resolve().parents[1] / "urdf" / "wip.urdf"


def test_second_read_uses_the_cache_without_yourdfpy(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    first = read_urdf(URDF)
    entries = list((tmp_path / "urdf").glob("*.pickle"))
    assert len(entries) == 1
    assert {"body", "wheel_left", "wheel_right"} <= set(first.link_names)
    code = ("import sys; from wheeled_dyn.models.urdf_source import read_urdf; "
            f"s = read_urdf({str(URDF)!r}); "
            "print(sorted(s.link_names), s.cylinder('wheel_left'), 'yourdfpy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={**os.environ, CACHE_ENV: str(tmp_path)}, check=True).stdout
    assert out.split()[-1] == "False", out               # yourdfpy was not imported
    assert str(sorted(first.link_names)) in out
    assert str(first.cylinder("wheel_left")) in out


def test_an_unreadable_entry_is_read_again(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    first = read_urdf(URDF)
    (entry,) = (tmp_path / "urdf").glob("*.pickle")
    entry.write_bytes(b"not a pickle")
    again = read_urdf(URDF)
    assert again.outline == first.outline
    assert entry.read_bytes() != b"not a pickle"          # replaced by a good entry


def test_a_rejected_file_is_not_cached(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="r"><link name="a"><visual><geometry><cylinder radius="x" '
                   'length="1"/></geometry></visual></link></robot>')
    for _ in range(2):
        with pytest.raises(InputFileError):
            read_urdf(bad)
    assert not list((tmp_path / "cache").glob("urdf/*.pickle"))
