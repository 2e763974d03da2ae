"""Worker preload of tests/python/test_dask_executor.py (`dask worker --preload THIS_FILE`): every
chunk a worker starts is logged to $OGK_TEST_DASK_DIR/chunks.log ("pid run_ids"), and a chunk that
holds run i while $OGK_TEST_DASK_DIR/kill-i exists kills its own worker (SIGKILL), once: the file is
renamed first, so the chunk flown again elsewhere runs normally; with $OGK_TEST_DASK_DIR/raise-i
instead, the chunk raises a KernelError (once); with hang-i, it sleeps 40 s first (once). The task is replaced by name in
ogk.sil.dask_executor, which is where the client's pickled reference to it resolves."""
from __future__ import annotations

import os
import signal
import time

from ogk_bindings.kernel import KernelError

from ogk.sil import dask_executor

# the worker may run a preload more than once: wrap the task itself, never the wrapper
_fly_chunk = getattr(dask_executor, "_unwrapped_fly_chunk", dask_executor.fly_chunk)
dask_executor._unwrapped_fly_chunk = _fly_chunk


def fly_chunk(shipment, seed, run_ids):   # noqa: ANN001, ANN201 - the wrapped task's signature
    where = os.environ.get("OGK_TEST_DASK_DIR")
    if where:
        with open(os.path.join(where, "chunks.log"), "a", encoding="utf-8") as fh:
            fh.write(f"{os.getpid()} {' '.join(str(int(i)) for i in run_ids)}\n")
        for i in run_ids:
            armed = os.path.join(where, f"hang-{int(i)}")
            if os.path.exists(armed):
                os.rename(armed, armed + ".done")
                time.sleep(40.0)
            armed = os.path.join(where, f"raise-{int(i)}")
            if os.path.exists(armed):
                os.rename(armed, armed + ".done")
                raise KernelError(7, "ogk_fake_step")
            armed = os.path.join(where, f"kill-{int(i)}")
            try:
                os.rename(armed, armed + ".done")
            except FileNotFoundError:
                continue
            # 3 s: the client has fetched the chunks this worker finished before, and the
            # scheduler's memory manager (a 2 s cycle) has dropped the shipment's extra replicas,
            # so half the time this worker holds its only copy (the executor must recover it)
            time.sleep(3.0)
            os.kill(os.getpid(), signal.SIGKILL)
    return _fly_chunk(shipment, seed, run_ids)


dask_executor.fly_chunk = fly_chunk
