"""The product-directory lock (ogk_host.dir_lock): while one process holds it, another cannot take it;
released, it can. Checked with util-linux's flock(1) in a separate process, on the lock file the
Python side names."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from ogk_host.dir_lock import directory_lock


def _try_lock(lock_file: Path) -> int:
    """flock -n's exit status: 0 when it took the lock, 1 when another process holds it."""
    return subprocess.run(["flock", "-n", str(lock_file), "true"], timeout=30).returncode


@pytest.mark.req("OGK-HAR-008")
def test_a_held_directory_lock_excludes_another_process(tmp_path: Path) -> None:
    products = tmp_path / "tables" / "leo_geo-0123456789ab"
    lock_file = products.parent / f".{products.name}.lock"
    with directory_lock(products):
        assert lock_file.is_file() and not products.exists()   # beside the directory, not in it
        assert _try_lock(lock_file) == 1
    assert _try_lock(lock_file) == 0
