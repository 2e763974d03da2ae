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


class Working:
    """A long step without a count (a ground solve, a closed-loop flight): its title, the time it has
    taken and, through `note(text)`, what it is doing now; on a terminal only. A context manager."""

    def __init__(self, title: str, enabled: bool | None = None) -> None:
        self.title = title
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self._bar: Any = None

    def __enter__(self) -> "Working":
        if self.enabled:
            import threading

            from tqdm import tqdm
            self._bar = tqdm(total=None, desc=self.title, bar_format="{desc} [{elapsed}] {postfix}",
                             leave=False, file=sys.stderr, mininterval=0.5)
            self._stop = threading.Event()
            self._clock = threading.Thread(target=self._tick, daemon=True)
            self._clock.start()
        return self

    def _tick(self) -> None:
        while not self._stop.wait(0.5):
            bar = self._bar
            if bar is not None:
                bar.refresh()

    def note(self, text: str) -> None:
        if self._bar is not None:
            self._bar.set_postfix_str(text)

    def __exit__(self, *exc: object) -> None:
        if self._bar is not None:
            self._stop.set()
            self._clock.join()
            self._bar.close()
            self._bar = None
