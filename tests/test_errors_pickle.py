"""Every error of the project survives a pickle round trip (a worker process's error reaches the
user as the same one-line message, with its data)."""

from __future__ import annotations

import importlib
import inspect
import pickle
import pkgutil
from pathlib import Path

import pytest

import wheeled_dyn
from wheeled_dyn.errors import InputFileError, LimitError, WheeledDynError

#: Sample constructor arguments by parameter name (anything else gets a string).
SAMPLES = {"path": Path("dir/file.toml"), "line": 7, "column": 3, "valid": ("a", "b"),
           "value": 1e9, "log": "server said no", "where": "file.toml:7"}


def _all_error_classes() -> list[type]:
    for info in pkgutil.walk_packages(wheeled_dyn.__path__, "wheeled_dyn."):
        if info.name.endswith("__main__"):
            continue
        try:
            importlib.import_module(info.name)
        except ImportError:            # an optional dependency missing: its errors are skipped
            continue
    found, todo = [], [WheeledDynError]
    while todo:
        cls = todo.pop()
        found.append(cls)
        todo.extend(cls.__subclasses__())
    return sorted(set(found), key=lambda c: f"{c.__module__}.{c.__qualname__}")


def _instance(cls: type) -> WheeledDynError:
    params = [p for p in inspect.signature(cls.__init__).parameters.values()
              if p.name != "self" and p.kind in (p.POSITIONAL_OR_KEYWORD, p.POSITIONAL_ONLY)]
    args = [SAMPLES.get(p.name, f"<{p.name}>") for p in params]
    return cls(*args)


CLASSES = _all_error_classes()


def test_the_tree_is_found():
    names = {c.__name__ for c in CLASSES}
    assert {"InputFileError", "DerivationError", "UnknownNameError", "LimitError",
            "DerivationNameError"} <= names


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_round_trip_keeps_type_message_and_data(cls):
    err = _instance(cls)
    back = pickle.loads(pickle.dumps(err))
    assert type(back) is cls
    assert str(back) == str(err)
    assert back.args == err.args
    public = {k: v for k, v in vars(err).items() if not k.startswith("_")}
    assert {k: v for k, v in vars(back).items() if not k.startswith("_")} == public


def test_keyword_arguments_and_later_attributes_survive():
    err = InputFileError(path="x.toml", reason="bad", line=2)
    err.hint = "added after construction"
    back = pickle.loads(pickle.dumps(err))
    assert (back.path, back.line, back.reason, back.hint) == (Path("x.toml"), 2, "bad",
                                                               "added after construction")
    assert str(back) == "x.toml:2: bad"


def test_limit_error_says_the_limit_and_why():
    err = LimitError("--samples", 0, "an integer from 1 to 100000", "memory")
    assert str(err) == "--samples = 0: expected an integer from 1 to 100000 (memory)"
    assert isinstance(err, ValueError)
