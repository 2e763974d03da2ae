"""Output paths are checked before a long computation starts, not after it."""
from __future__ import annotations

import os
from pathlib import Path

from ogk_host.errors import OgkInputError


def _nearest_existing(path: Path) -> Path:
    p = path
    while not p.exists() and p != p.parent:
        p = p.parent
    return p


def check_output_file(path: str | Path, option: str) -> Path:
    """A file the command will write: its directory must exist or be creatable, and be writable."""
    p = Path(path)
    if p.is_dir():
        raise OgkInputError("is a directory, expected a file", path=p, key=option)
    base = _nearest_existing(p.parent)
    if not base.is_dir():
        raise OgkInputError(f"{base} is not a directory", path=p, key=option)
    if not os.access(base, os.W_OK | os.X_OK) or (p.exists() and not os.access(p, os.W_OK)):
        raise OgkInputError("not writable", path=p, key=option)
    return p


def check_output_dir(path: str | Path, option: str) -> Path:
    """A directory the command will create or fill."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise OgkInputError("exists and is not a directory", path=p, key=option)
    base = _nearest_existing(p)
    if not base.is_dir() or not os.access(base, os.W_OK | os.X_OK):
        raise OgkInputError("not writable", path=p, key=option)
    return p
