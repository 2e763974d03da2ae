"""Output paths are checked before a long computation starts, not after it: the directory is
created (as the command would) and a probe file written and removed there. Results are written
atomically (`write_atomic`: a temporary file in the same directory, then a rename), and a result
file of an earlier command is removed when a new one starts (`remove_stale`), so a file that
exists is always complete and always the latest command's."""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

from ogk_bindings.errors import OgkInputError


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


def remove_stale(path: str | Path) -> None:
    """Removes an earlier result file before the command that will rewrite it starts."""
    try:
        Path(path).unlink()
    except FileNotFoundError:
        pass


def write_atomic(path: str | Path, text: str) -> None:
    """Writes `text` to `path` through a temporary file in the same directory and a rename: the
    file is either the old one, absent, or complete."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=p.parent, prefix=f".{p.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, p)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
