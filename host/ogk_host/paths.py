"""Where ogk reads what it ships and writes what it makes, run from the repository or from an installed
wheel (docs/guides/install.md).

* `SOURCE_TREE`: the repository this package runs from (a clone, the Makefile's editable install), or
  None when it runs from an installed wheel (site-packages).
* `SCENARIO_DIR`: the shipped scenarios: the repository's scenarios/, or the wheel's copy of them, the
  package data ogk_host/scenarios/ (found with importlib.resources).
* `WORK_ROOT`: where products go by default (build/tables/<name>-<sha12>, build/pil/...): the
  repository, or the current directory outside it.
* `need_repository(what)`: the repository, or one OgkInputError line saying that `what` needs it (the
  flight programs of `--target m7` are built by the repository's Makefile).
"""
from __future__ import annotations

import importlib.resources
from pathlib import Path

from ogk_bindings.errors import OgkInputError

_HERE = Path(__file__).resolve().parent          # host/ogk_host, or site-packages/ogk_host


def _source_tree() -> Path | None:
    root = _HERE.parents[1]
    if (root / "kernel" / "include" / "ogk" / "version.h").is_file() and (root / "Makefile").is_file():
        return root
    return None


def _scenario_dir() -> Path:
    if SOURCE_TREE is not None:
        return SOURCE_TREE / "scenarios"
    shipped = importlib.resources.files("ogk_host") / "scenarios"
    # an installed wheel is unpacked on disk: the scenarios are files with paths (hashed, recorded)
    return Path(str(shipped))


SOURCE_TREE: Path | None = _source_tree()
SCENARIO_DIR: Path = _scenario_dir()
WORK_ROOT: Path = SOURCE_TREE if SOURCE_TREE is not None else Path.cwd()


def need_repository(what: str, key: str | None = None) -> Path:
    """The repository; from an installed wheel, OgkInputError: `what` needs it."""
    if SOURCE_TREE is None:
        raise OgkInputError(f"{what} needs the ogk repository (git clone, then make; docs/guides/install.md), "
                            "not an installed wheel", key=key)
    return SOURCE_TREE
