"""Progress of anything longer than a few seconds, on a terminal only (tqdm on stderr): runs done,
failures so far, rate and time left. Quiet when stderr is not a terminal (CI, pipes, tests)."""
from __future__ import annotations

import sys
from typing import Any


class Progress:
    """A bar over `total` items; `advance(n, failed)` after each finished chunk."""

    def __init__(self, title: str, total: int, enabled: bool | None = None, done: int = 0,
                 unit: str = "run") -> None:
        if enabled is None:
            enabled = sys.stderr.isatty()
        self.failed = 0
        self._bar: Any = None
        if enabled and total > 0:
            from tqdm import tqdm
            self._bar = tqdm(total=total, initial=done, desc=title, unit=unit, leave=False,
                             dynamic_ncols=True, file=sys.stderr)
            self._bar.set_postfix(failed=0)

    def advance(self, n: int, failed: int = 0) -> None:
        self.failed += failed
        if self._bar is not None:
            self._bar.update(n)
            self._bar.set_postfix(failed=self.failed)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
