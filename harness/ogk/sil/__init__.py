"""Mission-independent software-in-the-loop machinery: campaign runner, failure criteria, reports.

Importing it puts BLAS on one thread in this process (the libraries loaded now through
threadpoolctl, those loaded later through OPENBLAS_NUM_THREADS / OMP_NUM_THREADS / MKL_NUM_THREADS,
unless the environment already sets them): a multi-threaded BLAS splits its sums by the machine's
core count, so the same plan and run gave MPSP results differing in the 7th digit between a 2-core
process and a single-threaded Dask worker. On one thread a run's numbers are the same on every
machine and executor (docs/guides/scale-out.md). Every family imports ogk.sil before it builds a plan.
"""
import os as _os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    _os.environ.setdefault(_name, "1")

from threadpoolctl import threadpool_limits as _threadpool_limits  # noqa: E402

_threadpool_limits(limits=1, user_api="blas")
