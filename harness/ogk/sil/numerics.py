"""What a run's numbers depend on in this process besides the code and its inputs: the numerics
fingerprint of the host (docs/guides/scale-out.md, "Bit for bit across machines").

The flight software is C compiled once, but the truth models, the dispersions and the ground
products' interpolation run through numpy and its BLAS, and both pick their kernels from the CPU at
load time: OpenBLAS its core type (Haswell, SkylakeX, Zen, ...), numpy its SIMD dispatch targets
(AVX2, AVX-512, ...). Two machines with different choices give different last bits, and a chaotic
flight (a perturbed NMPC rendezvous) can then end elsewhere (measured: notes/session-12.md).

So a campaign records the fingerprint in its envelope, a Dask shipment carries the client's, and a
worker whose fingerprint differs refuses the chunk (ogk.sil.shipping.plan_of) instead of returning
records that are not the local executor's. `OPENBLAS_CORETYPE` and `NPY_DISABLE_CPU_FEATURES`, set
the same on every machine before Python starts, make a mixed cluster's fingerprints equal.
"""
from __future__ import annotations

import functools
import platform
import sys

import numpy as np


def _numpy_simd() -> str:
    """numpy's SIMD dispatch targets that this CPU enables (numpy >= 1.22 internals, read only)."""
    try:
        from numpy._core import _multiarray_umath as um  # numpy 2
    except ImportError:                                   # pragma: no cover (numpy 1.x)
        from numpy.core import _multiarray_umath as um    # type: ignore[no-redef]
    features = getattr(um, "__cpu_features__", {})
    dispatch = getattr(um, "__cpu_dispatch__", [])
    baseline = getattr(um, "__cpu_baseline__", [])
    return ",".join([*baseline, *(t for t in dispatch if features.get(t))])


def _blas() -> str:
    """Each BLAS numpy/scipy loaded: its implementation, version and CPU kernel choice."""
    from threadpoolctl import threadpool_info
    libs = sorted(f"{i.get('internal_api')} {i.get('version')} {i.get('architecture')}"
                  for i in threadpool_info() if i.get("user_api") == "blas")
    return "; ".join(libs)


def fingerprint() -> dict[str, str]:
    """The numerics fingerprint of this process (module doc): name -> value, all strings."""
    return dict(_fingerprint())


@functools.lru_cache(maxsize=1)
def _fingerprint() -> tuple[tuple[str, str], ...]:
    """Made once per process: the kernels are chosen when the libraries load."""
    import scipy
    import scipy.linalg  # noqa: F401  (loads scipy's BLAS, so that it is listed)
    return (("machine", platform.machine()), ("byteorder", sys.byteorder),
            ("python", platform.python_version()), ("numpy", np.__version__),
            ("scipy", scipy.__version__), ("numpy_simd", _numpy_simd()), ("blas", _blas()))


def differences(ours: dict[str, str], theirs: dict[str, str],
                where: str = "on the client") -> list[str]:
    """'name: ours here, theirs <where>' for each entry that differs, sorted by name."""
    return [f"{k}: {ours.get(k)!r} here, {theirs.get(k)!r} {where}"
            for k in sorted(set(ours) | set(theirs)) if ours.get(k) != theirs.get(k)]
