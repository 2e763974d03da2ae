"""Shared fixtures of the harness tests (kernel through the cffi bindings)."""
from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture
def rng() -> np.random.Generator:
    """Fixed seed: every run checks the same random cases (reproducible failures)."""
    return np.random.default_rng(20261122)
