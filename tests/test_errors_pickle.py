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


def _real_errors() -> dict[type, list[WheeledDynError]]:
    r"""Each error class of :mod:`wheeled_dyn.errors`, made as the package makes it: with the
    registry's models (a dict of entries holding functions), a coordinate set table (a
    mapping proxy), NumPy values, a function as a bad argument."""
    import numpy as np

    from wheeled_dyn import errors
    from wheeled_dyn.coordinates.builtin import builtin_specs
    from wheeled_dyn.models.registry import MODELS, load_model
    specs = builtin_specs(load_model("wip"))
    return {
        errors.WheeledDynError: [errors.WheeledDynError("plain message")],
        errors.InputFileError: [errors.InputFileError(Path("robot.urdf"), "malformed XML",
                                                      line=3, column=9)],
        errors.UnknownNameError: [
            errors.UnknownNameError("model", "nope", MODELS, where="names"),
            errors.UnknownNameError("coordinate set", "nope", specs, where="model wip"),
            errors.UnknownNameError("link", "x", (n for n in ("a", "b")))],
        errors.ModelError: [errors.ModelError("wip", "wheel_left", "radius 0 is not positive")],
        errors.InertiaError: [errors.InertiaError("robot", "caster",
                                                  "inertia violates the triangle inequality")],
        errors.ParameterError: [errors.ParameterError("m_S", np.float64(-1.0), "positive")],
        errors.StateError: [errors.StateError("phi", np.array([np.nan, 1.0]), "finite")],
        errors.DerivationError: [errors.DerivationError("eq.toml", "A[1,2]", "bad", line=4)],
        errors.OptionalDependencyError: [errors.OptionalDependencyError(
            "the viewer", "meshcat", "pip install meshcat")],
        errors.LimitError: [errors.LimitError("--samples", np.int64(0), "1 to 100000")],
        errors.WorkerError: [errors.WorkerError("ended", (f for f in ("a.toml", "b.toml")))],
        errors.ArgumentError: [errors.ArgumentError("matrices", "phi", "abc", "a number"),
                               errors.ArgumentError("simulate", "u", lambda t: t, "inputs"),
                               errors.ArgumentError("load_model", "name", (i for i in ()),
                                                    "a name")],
    }


def _same(a: object, b: object) -> bool:
    import numpy as np
    if isinstance(a, np.ndarray):
        return isinstance(b, np.ndarray) and np.array_equal(a, b, equal_nan=True)
    try:
        return bool(a == b)
    except Exception:
        return False


def test_every_error_class_of_errors_py_pickles_with_real_data():
    from wheeled_dyn import errors
    made = _real_errors()
    defined = {c for c in vars(errors).values()
               if isinstance(c, type) and issubclass(c, WheeledDynError)}
    assert defined == set(made), f"add real data for {defined - set(made)}"
    for cls, instances in made.items():
        for err in instances:
            back = pickle.loads(pickle.dumps(err))
            again = pickle.loads(pickle.dumps(back))          # and once more
            for copy in (back, again):
                assert type(copy) is cls and str(copy) == str(err)
                for key, value in vars(err).items():
                    if key.startswith("_"):
                        continue
                    got = getattr(copy, key)
                    # a value that cannot be pickled (a function) travels as its repr
                    assert _same(got, value) or got == repr(value), (cls, key, got, value)
