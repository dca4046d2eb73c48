"""Shared fixtures: seeded random generators, models with random physical parameters.

Comparison results are not reused from the disk cache in the tests (each test computes what it
checks: ``WHEELED_DYN_REUSE=forms`` keeps only the printed and compiled forms and the closed
forms); tests/test_result_cache.py and tests/test_cache_trust.py turn reuse on where they test
it.
"""

from __future__ import annotations

import os

import numpy as np
import pytest

os.environ["WHEELED_DYN_REUSE"] = "forms"       # also for the CLI subprocesses the tests start

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
