"""Reproducible per-run random streams, the same for every mission.

Run i of a campaign with master seed S owns the generator
  PCG64(run_seed_i),  run_seed_i = SeedSequence(S, spawn_key=(i,)).generate_state(1, uint64)[0],
so its numbers depend on (S, i) only, never on the number of runs, the worker count or the chunking.
"""
from __future__ import annotations

import numpy as np


def run_seed(master_seed: int, run_id: int) -> int:
    """The 64-bit seed of run `run_id` of a campaign with `master_seed`."""
    ss = np.random.SeedSequence(int(master_seed), spawn_key=(int(run_id),))
    return int(ss.generate_state(1, np.uint64)[0])


def run_generator(seed_of_run: int) -> np.random.Generator:
    """The generator of one run."""
    return np.random.Generator(np.random.PCG64(int(seed_of_run)))
