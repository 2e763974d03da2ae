"""The kernel precision a process flies: `--precision double|single` of `ogk mc` and `ogk run`.

The kernel's real type (ogk/real.h) is fixed per process when the bindings are first imported
(ogk_bindings._ffi reads the environment variable ``OGK_PRECISION``: the double extension, the default,
or the float kernel's ``_ogk_cffi_single``). So the option is read before anything imports them
(`select`, called by the CLI before the scenario's family is loaded), and it is set in the environment,
which every worker process inherits: the forked workers of ogk.sil.runner (which also inherit the loaded
extension), the processes of a Dask `local:N` cluster. A worker that loaded the other precision (a remote
Dask worker started without ``OGK_PRECISION``) refuses the campaign (`check_options`, ogk.sil.shipping).

A single-precision campaign says so in its plan's options (``"precision": "single"``: its run log's key,
its envelope and its shipment), and the envelope records ``"precision"``; a double campaign's options,
run log and envelope are as they were before the option existed.
"""
from __future__ import annotations

import os
import sys
from collections.abc import Mapping, MutableSequence
from typing import Any

from ogk_bindings.errors import OgkInputError

#: the real type of the kernel each target flies: the host's is the process's (this module's `current`,
#: "double" unless --precision single); the Cortex-M4F's flight programs are built on the float kernel
#: (port/cortex-m4f: M4F_PRECISION), the others' on the double one
TARGET_PRECISION = {"host": "double", "m7": "double", "sparc": "double", "m4f": "single"}
#: the environment variable ogk_bindings._ffi reads (its PRECISION_ENV), and the precisions
ENV = "OGK_PRECISION"
CHOICES = ("double", "single")
DEFAULT = "double"
OPTION = "--precision"
HELP = ("the kernel's real type flown: double (default) or single (the kernel built with "
        "OGK_REAL_SINGLE=1, float, as on a single-precision FPU; F32 tables; "
        "docs/guides/campaigns.md, \"Single precision\")")


def _loaded() -> str | None:
    """The precision of the bindings already imported in this process, or None."""
    ffi_module = sys.modules.get("ogk_bindings._ffi")
    return None if ffi_module is None else str(getattr(ffi_module, "PRECISION"))


def select(precision: str) -> str:
    """Sets this process's (and its future children's) precision before the bindings are imported.
    OgkInputError for an unknown value, or when the bindings are already loaded in the other one."""
    if precision not in CHOICES:
        raise OgkInputError(f"expected one of {', '.join(CHOICES)}, got {precision!r}", key=OPTION)
    loaded = _loaded()
    if loaded is not None and loaded != precision:
        raise OgkInputError(f"this process already loaded the {loaded}-precision kernel bindings; "
                            f"{precision} needs a new process ({ENV}={precision})", key=OPTION)
    os.environ[ENV] = precision
    return precision


def take(rest: MutableSequence[str], remove: bool = False) -> str | None:
    """The value of `--precision X` / `--precision=X` in a command's arguments (None when absent);
    with `remove` the option is taken out of `rest` (a parser that does not declare it)."""
    for i, arg in enumerate(rest):
        if arg == "--":
            return None
        if arg == OPTION:
            if i + 1 >= len(rest):
                raise OgkInputError("needs double or single", key=OPTION)
            value = rest[i + 1]
            if remove:
                del rest[i:i + 2]
            return value
        if arg.startswith(OPTION + "="):
            if remove:
                del rest[i]
            return arg.split("=", 1)[1]
    return None


def current() -> str:
    """This process's precision (imports the bindings: after `select`)."""
    from ogk_bindings._ffi import PRECISION
    return str(PRECISION)


def check(precision: str, target: str = "host") -> None:
    """The precision a campaign asks for is the one this process flies (the CLI selected it before
    the family was loaded), on the host."""
    if precision not in CHOICES:
        raise OgkInputError(f"expected one of {', '.join(CHOICES)}, got {precision!r}", key=OPTION)
    if current() != precision:
        raise OgkInputError(f"this process flies the {current()}-precision kernel: set {ENV}={precision} "
                            f"before it starts, or give {OPTION} on the `ogk` command line", key=OPTION)
    if precision != DEFAULT and target != "host":
        raise OgkInputError(f"{OPTION} {precision} flies the kernel on the host only (the target's flight "
                            f"program is built on its own), got --target {target}", key=OPTION)


def stamp(options: Mapping[str, Any]) -> dict[str, Any]:
    """A plan's options with this process's precision when it is not the default (a double plan's
    options unchanged: its run log and envelope are those of before)."""
    p = current()
    return dict(options) if p == DEFAULT else {**options, "precision": p}


def of_options(options: Mapping[str, Any]) -> str:
    """The precision a plan's options say (absent: double)."""
    return str(options.get("precision", DEFAULT))


def check_options(options: Mapping[str, Any]) -> None:
    """A worker flies a plan only in the precision its options say (ogk.sil.shipping.plan_of)."""
    want = of_options(options)
    if current() != want:
        raise OgkInputError(f"this worker loaded the {current()}-precision kernel, the campaign flies "
                            f"{want}: start the workers with {ENV}={want}", key=OPTION)


#: binary32's epsilon: the float kernel's OGK_REAL_EPSILON
SINGLE_EPS = 2.0 ** -23
#: the NMPC solver's tolerances on a single-precision kernel, host (SIL) or target (the M4F's flight
#: configuration): a feasibility or objective change of 1e-9 (the double law's) is below the rounding of
#: the residuals themselves, and the rendezvous found no first plan (M4F; host: 2 of 2 runs lost with 6
#: failed solves, seed 51205). Feasibility and objective 64 eps (7.6e-6, a few roundings of the normalised
#: residual summed over the nodes), stationarity sqrt(eps) (3.5e-4, the accuracy of a gradient whose
#: cancellation loses half the digits). A tolerance already above its floor is kept; the kernel floors
#: tol_feas and tol_obj itself too (nmpc_sqp.c, docs/design/nmpc-flight.md, "2g. Single precision").
NMPC_SINGLE_FLOORS = {"tol_feas": 64 * SINGLE_EPS, "tol_obj": 64 * SINGLE_EPS, "tol_stat": SINGLE_EPS ** 0.5}


def nmpc_tolerances(settings: Mapping[str, Any], real: str) -> dict[str, Any]:
    """`settings` (NMPC configuration fields) for a kernel of precision `real`: the tolerances it names
    floored at NMPC_SINGLE_FLOORS when single, unchanged when double."""
    out = dict(settings)
    if real == "single":
        for name, floor in NMPC_SINGLE_FLOORS.items():
            if name in out:
                out[name] = max(float(out[name]), floor)
    return out

