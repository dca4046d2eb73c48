"""Shared fixtures: seeded random generators, models with random physical parameters.

Comparison results are not reused from the disk cache in the tests (each test computes what it
checks); tests/test_result_cache.py turns reuse on where it tests it.
"""

from __future__ import annotations

import os

import numpy as np
import pytest

os.environ["WHEELED_DYN_REUSE"] = "0"           # also for the CLI subprocesses the tests start

#: Seed of every random generator in the tests.
SEED = 20261122
#: Random parameter sets per structural test.
N_PARAM_SETS = 4
#: Random states per parameter set.
N_STATES = 5


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(SEED)


def random_wip_models(n: int = N_PARAM_SETS, seed: int = SEED):
    from wheeled_dyn import load_model, random_wip_parameters
    rng = np.random.default_rng(seed)
    return [load_model("wip", random_wip_parameters(rng)) for _ in range(n)]
