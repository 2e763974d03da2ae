"""An exclusive lock on a product directory, held while it is checked or (re)generated.

Two processes that need the same cached ground products at once (two campaigns of one scenario in two
terminals, Dask workers, the test suite's workers) would otherwise both find the directory empty and
write the same files, one reading what the other has half written. The lock is a file beside the
directory (`.NAME.lock` in its parent), so the directory itself holds only products."""
from __future__ import annotations

import fcntl
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path


@contextmanager
def directory_lock(directory: Path) -> Iterator[None]:
    """Holds an exclusive flock on DIRECTORY's lock file for the block (waits for another holder)."""
    directory = Path(directory)
    directory.parent.mkdir(parents=True, exist_ok=True)
    with open(directory.parent / f".{directory.name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        yield
