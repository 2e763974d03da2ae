"""The optional packages of ogk and the one way every layer imports them (docs/guides/install.md).

The heavy peers are pip extras, not dependencies: a user who flies campaigns does not install Basilisk.
Code that needs one imports it through `need`, which raises `MissingExtra` (an OgkInputError: the `ogk`
command prints one line and exits with 2) naming the extra that brings it:

    ogk mc: ogk[dask] is needed for ogk mc --dask: pip install 'ogk[dask]'

| extra      | packages            | what needs them                                                    |
|------------|---------------------|--------------------------------------------------------------------|
| `basilisk` | bsk (Basilisk)      | ogk.missions.orbit_injection.basilisk (docs/guides/basilisk.md)           |
| `dask`     | dask[distributed]   | `ogk mc --dask` (ogk.sil.dask_executor, docs/guides/scale-out.md)         |
| `peers`    | daqp                | the QP peers of `make bench` (tests/bench)                         |

CasADi is not an extra: the proximity family's ground plan is solved by CasADi + IPOPT before every
campaign, and the rendezvous family's ground models are CasADi expressions.
"""
from __future__ import annotations

import importlib
from types import ModuleType

from .errors import OgkInputError

#: extra -> the distributions it installs (pyproject.toml [project.optional-dependencies])
EXTRAS = {"basilisk": ("bsk",), "dask": ("dask[distributed]",), "peers": ("daqp",)}


class MissingExtra(OgkInputError):
    """An optional package is not installed: one line naming the extra that brings it."""

    def __init__(self, extra: str, purpose: str) -> None:
        self.extra = extra
        super().__init__(f"ogk[{extra}] is needed for {purpose}: pip install 'ogk[{extra}]'")


def need(module: str, extra: str, purpose: str) -> ModuleType:
    """`import module` (a dotted name: a submodule is imported as `from A import b` would), or
    MissingExtra naming `extra` when the module's top-level package is not installed. A package that
    is installed but fails to import (one of its own dependencies missing) raises its own error."""
    if extra not in EXTRAS:
        raise ValueError(f"no extra {extra!r} (ogk_bindings.extras.EXTRAS)")
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        top = module.partition(".")[0]
        if exc.name is None or exc.name.partition(".")[0] != top:
            raise
        raise MissingExtra(extra, purpose) from exc
