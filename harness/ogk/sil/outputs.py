"""Output paths are checked before a long computation starts, not after it: the directory is
created (as the command would) and a probe file written and removed there."""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

from ogk_host.errors import OgkInputError


def _probe(directory: Path, shown: Path, option: str) -> None:
    try:
        directory.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=directory, prefix=".ogk-probe-"):
            pass
    except OSError as exc:
        raise OgkInputError(f"not writable ({exc.strerror or exc})", path=shown, key=option) from None


def check_output_file(path: str | Path, option: str) -> Path:
    """A file the command will write: its directory must be creatable and writable."""
    p = Path(path)
    if p.is_dir():
        raise OgkInputError("is a directory, expected a file", path=p, key=option)
    if p.parent.exists() and not p.parent.is_dir():
        raise OgkInputError(f"{p.parent} is not a directory", path=p, key=option)
    _probe(p.parent, p, option)
    if p.exists():
        try:
            with open(p, "ab"):
                pass
        except OSError as exc:
            raise OgkInputError(f"not writable ({exc.strerror})", path=p, key=option) from None
    return p


def check_output_dir(path: str | Path, option: str) -> Path:
    """A directory the command will create or fill. An existing one is not probed (nothing is
    written into a directory before the command has decided that it may)."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise OgkInputError("exists and is not a directory", path=p, key=option)
    if p.is_dir():
        if not os.access(p, os.W_OK | os.X_OK):
            raise OgkInputError("not writable", path=p, key=option)
        return p
    _probe(p, p, option)
    return p
