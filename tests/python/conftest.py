"""Shared fixtures of the harness tests (kernel through the cffi bindings)."""
from __future__ import annotations

import signal

import numpy as np
import pytest


def pytest_configure(config: pytest.Config) -> None:
    """The `req` marker: the requirements of docs/evidence/requirements.md a test verifies (collected by
    tests/trace/check_trace.py from the source, `make trace`; pytest itself only registers it)."""
    config.addinivalue_line("markers", "req(*ids): requirements verified (OGK-XXX-NNN, docs/evidence/requirements.md)")


@pytest.fixture
def rng() -> np.random.Generator:
    """Fixed seed: every run checks the same random cases (reproducible failures)."""
    return np.random.default_rng(20261122)


@pytest.fixture
def alarm(request: pytest.FixtureRequest):
    """A hang is a failure, not a stuck job: the test ends within the module's ALARM_S seconds
    (campaign tests: `pytestmark = pytest.mark.usefixtures("alarm")`)."""
    limit = int(getattr(request.module, "ALARM_S", 90))

    def expired(signum, frame):
        raise TimeoutError(f"test took more than {limit} s: a campaign hung")
    old = signal.signal(signal.SIGALRM, expired)
    signal.alarm(limit)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)
