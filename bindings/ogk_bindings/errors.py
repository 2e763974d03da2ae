"""Errors a person can act on: one line naming the file, the key and the reason.

Ground tools and the SIL harness raise `OgkInputError` for bad input (scenario files, table
directories, command-line values); the `ogk` command prints its message alone and exits with 2
(a traceback only with --debug). Raise it before any long computation starts.
"""
from __future__ import annotations

from pathlib import Path


class OgkInputError(Exception):
    """Bad input, reported as ``FILE: KEY: REASON`` (file and key optional)."""

    def __init__(self, reason: str, *, path: str | Path | None = None, key: str | None = None) -> None:
        self.reason = reason
        self.path = None if path is None else str(path)
        self.key = key
        super().__init__(self.line())

    def line(self) -> str:
        parts = [p for p in (self.path, self.key) if p]
        return ": ".join([*parts, self.reason])


class TableError(OgkInputError):
    """A table directory that does not belong to the scenario flown, or whose files are corrupted."""
