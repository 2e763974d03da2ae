"""The Dask executor of the campaign engine (ogk.sil.dask_executor, ogk.sil.shipping;
docs/guides/scale-out.md) against the local one, on a scheduler and two single-threaded workers started
here on 127.0.0.1 (`dask scheduler`, `dask worker`, as on a cluster):
  * every family's campaign gives the local executor's records bit for bit (timing keys aside),
    and so does a `--target m7` campaign (one family, one run);
  * a worker killed mid-campaign costs only its chunk: that chunk is flown again on another worker,
    every other chunk once, and the records are the local ones;
  * a campaign started on one executor resumes on the other, both ways (the engine's run log);
  * the shipped products are checked on the worker: a copy that differs is refused, never used;
  * `ogk mc --dask local:1` writes the local campaign's table; a bad --dask is one line, exit 2.
The reference is the local executor's campaign (one process), itself checked against the paper
and closed forms by the families' own tests. Runs are few (1-4 per test) to keep this cheap."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from ogk_host.scenario_file import read_header, resolve_scenario

from ogk.cli import main
from ogk.missions import registry
from ogk.sil import dask_executor, envelope, shipping
from ogk.sil.dask_executor import DaskExecutor
from ogk.sil.engine import fly_campaign
from ogk.sil.runner import CampaignAborted, Watchdog
from ogk_bindings.errors import OgkInputError
from test_campaign_engine import CLI_OPTIONS, ogk, plan_of, same, without_timing
from test_campaign_engine import FAMILIES as ENGINE_FAMILIES

#: the shipped families (the test family of test_campaign_engine is registered in its own process
#: only: a Dask worker would not know it)
FAMILIES = {name: row for name, row in ENGINE_FAMILIES.items() if name in registry.PACKAGES}

HERE = Path(__file__).resolve().parent
#: every in-process test ends within this many seconds (conftest.alarm); the first one on a family
#: waits for both workers to rebuild its plan (the binary family's nominal transfer: ~30 s)
ALARM_S = 300
pytestmark = pytest.mark.usefixtures("alarm")


def _start(args: list[str], log: Path, env: dict[str, str]) -> subprocess.Popen[bytes]:
    with open(log, "wb") as fh:
        return subprocess.Popen([sys.executable, "-m", *args], stdout=fh, stderr=subprocess.STDOUT,
                                env=env)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A scheduler and two workers (one thread each, nanny-restarted) on 127.0.0.1; yields
    (scheduler address, the preload's directory: chunks.log and kill-<run> files)."""
    where = tmp_path_factory.mktemp("dask")
    env = {**os.environ, "OGK_TEST_DASK_DIR": str(where)}
    sched_file = where / "scheduler.json"
    procs = [_start(["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
                     "--no-dashboard", "--scheduler-file", str(sched_file)],
                    where / "scheduler.log", env)]
    try:
        deadline = time.monotonic() + 60.0
        while not sched_file.exists() and time.monotonic() < deadline:
            time.sleep(0.2)
        address = json.loads(sched_file.read_text())["address"]
        for k in range(2):
            procs.append(_start(["distributed.cli.dask_worker", address, "--nthreads", "1",
                                 "--nworkers", "1", "--host", "127.0.0.1", "--no-dashboard",
                                 "--name", f"w{k}", "--preload",
                                 str(HERE / "dask_worker_faults.py")],
                                where / f"worker{k}.log", env))
        from distributed import Client
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(2, timeout=60)
        yield address, where
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in reversed(procs):
            try:
                p.wait(10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait(5)


def family_object(family: str):
    scenario, _ = FAMILIES[family]
    return registry.family(read_header(resolve_scenario(scenario)))


def chunk_log(where: Path) -> list[tuple[int, ...]]:
    path = where / "chunks.log"
    lines = path.read_text().splitlines() if path.exists() else []
    return [tuple(int(i) for i in line.split()[1:]) for line in lines]


#: runs per chunk of the bit-for-bit test: one chunk per worker, but the binary family's first chunk
#: on a worker rebuilds its nominal transfer (~30 s of CPU): one chunk, one worker
CHUNK_RUNS = {"binary-asteroid": 2}


@pytest.mark.req("OGK-HAR-017", "OGK-HAR-001")
@pytest.mark.parametrize("family", FAMILIES)
def test_dask_records_are_the_local_ones_bit_for_bit(family, cluster):
    address, _ = cluster
    plan = plan_of(family)
    local = fly_campaign(plan, 2, 23, workers=1, progress=False)
    with DaskExecutor(address, family_object(family)) as ex:
        remote = fly_campaign(plan, 2, 23, chunk_runs=CHUNK_RUNS.get(family, 1), executor=ex,
                              progress=False)
    assert remote.workers == 2 and remote.run_ids == [0, 1]
    assert same(without_timing(remote.records), without_timing(local.records))


@pytest.mark.req("OGK-HAR-017", "OGK-HAR-012")
def test_dask_target_m7_campaign_is_the_local_one(cluster):
    address, _ = cluster
    scenario, _ = FAMILIES["low-thrust-transfer"]
    header = read_header(resolve_scenario(scenario))
    fam = registry.family(header)
    plan = fam.plan(header, {"target": "m7"})
    assert plan.target == "m7" and "flight_program" in plan.products
    local = fly_campaign(plan, 1, 5, workers=1, progress=False)
    with DaskExecutor(address, fam) as ex:
        remote = fly_campaign(plan, 1, 5, executor=ex, progress=False)
    assert any(k.startswith("pil.") for k in remote.records[0])
    assert same(without_timing(remote.records), without_timing(local.records))


@pytest.mark.req("OGK-HAR-017", "OGK-HAR-003")
def test_a_worker_killed_mid_campaign_costs_only_its_chunk(cluster, tmp_path):
    address, where = cluster
    family = "low-thrust-rendezvous"
    plan = plan_of(family)
    local = fly_campaign(plan, 4, 41, workers=1, progress=False)
    before = len(chunk_log(where))
    (where / "kill-2").touch()                 # the chunk of run 2 kills its worker, once
    with DaskExecutor(address, family_object(family)) as ex:
        remote = fly_campaign(plan, 4, 41, chunk_runs=1, executor=ex, progress=False,
                              run_log=tmp_path / "k.json.runs.jsonl")
    assert (where / "kill-2.done").exists()
    flown = chunk_log(where)[before:]
    assert sorted(flown) == [(0,), (1,), (2,), (2,), (3,)], flown
    assert same(without_timing(remote.records), without_timing(local.records))


@pytest.mark.req("OGK-HAR-017", "OGK-HAR-003")
def test_a_run_that_raises_on_a_worker_aborts_naming_its_chunk_and_status(cluster):
    address, where = cluster
    family = "low-thrust-rendezvous"
    (where / "raise-3").touch()
    with DaskExecutor(address, family_object(family)) as ex:
        with pytest.raises(CampaignAborted) as err:
            fly_campaign(plan_of(family), 4, 41, chunk_runs=2, executor=ex, progress=False)
    assert err.value.run_ids == [2, 3] and "KernelError" in err.value.reason
    assert err.value.status is not None


@pytest.mark.req("OGK-HAR-017", "OGK-HAR-003")
def test_watchdog_names_the_hung_chunk(cluster, monkeypatch):
    address, where = cluster
    family = "low-thrust-rendezvous"
    monkeypatch.setattr(dask_executor, "PLAN_ALLOWANCE_S", 0.0)
    (where / "hang-1").touch()
    start = time.perf_counter()
    with DaskExecutor(address, family_object(family)) as ex:
        with pytest.raises(CampaignAborted) as err:
            fly_campaign(plan_of(family), 2, 41, chunk_runs=1, executor=ex, progress=False,
                         watchdog=Watchdog(base_s=8.0, per_run_s=0.0))
    # the hung chunk is named (run 0's may still be in flight on a crowded machine)
    assert 1 in err.value.run_ids and set(err.value.run_ids) <= {0, 1}
    assert "watchdog" in err.value.reason and time.perf_counter() - start < 40.0


@pytest.mark.req("OGK-HAR-017", "OGK-HAR-004")
def test_resume_across_executors_both_ways(cluster, tmp_path):
    address, _ = cluster
    family = "low-thrust-transfer"
    plan = plan_of(family)
    whole = fly_campaign(plan, 4, 13, workers=1, progress=False)
    fam = family_object(family)
    # started locally (runs 0-1 kept in the log), finished on Dask
    log = tmp_path / "a.json.runs.jsonl"
    fly_campaign(plan, 4, 13, workers=1, run_ids=[0, 1], run_log=log, progress=False)
    with DaskExecutor(address, fam) as ex:
        resumed = fly_campaign(plan, 4, 13, chunk_runs=1, executor=ex, run_log=log, resume=True,
                               progress=False)
    assert resumed.resumed_runs == 2
    assert same(without_timing(resumed.records), without_timing(whole.records))
    # started on Dask (runs 1 and 3), finished locally
    log = tmp_path / "b.json.runs.jsonl"
    with DaskExecutor(address, fam) as ex:
        fly_campaign(plan, 4, 13, run_ids=[1, 3], chunk_runs=1, executor=ex, run_log=log,
                     progress=False)
    resumed = fly_campaign(plan, 4, 13, workers=2, run_log=log, resume=True, progress=False)
    assert resumed.resumed_runs == 2
    assert same(without_timing(resumed.records), without_timing(whole.records))


@pytest.mark.req("OGK-HAR-017", "OGK-HAR-008")
def test_shipped_products_are_checked_by_sha256_on_the_worker(tmp_path):
    plan = plan_of("orbit-injection")
    shipment = shipping.ship(plan, family_object("orbit-injection"))
    names = {Path(f.path).name for f in shipment.files}
    assert "nog_bundle.ogkt" in names and "manifest.json" in names
    bundle = next(f for f in shipment.files if f.path.endswith("nog_bundle.ogkt"))
    assert bundle.sha256 == plan.products["nog_tables"]["nog_bundle.ogkt"]
    # a missing file is written and checked; an existing copy that differs is refused
    target = tmp_path / "products" / "t.bin"
    fresh = shipping.ShippedFile(str(target), False, bundle.sha256, bundle.data)
    assert shipping.materialise(fresh).read_bytes() == bundle.data
    target.write_bytes(bundle.data[:-1] + bytes([bundle.data[-1] ^ 1]))
    with pytest.raises(OgkInputError, match="differs from the campaign"):
        shipping.materialise(fresh)
    assert target.read_bytes() != bundle.data          # refused, not overwritten
    torn = shipping.ShippedFile(str(tmp_path / "u.bin"), False, bundle.sha256, bundle.data[:-1])
    with pytest.raises(OgkInputError, match="do not match their SHA-256"):
        shipping.materialise(torn)


@pytest.mark.req("OGK-HAR-017")
def test_a_worker_with_other_numerics_refuses_the_chunk():
    """A worker whose BLAS picked other kernels (OPENBLAS_CORETYPE=Sandybridge, which changes a
    perturbed NMPC flight's end: notes/session-12.md) and whose numpy dispatches less SIMD
    has another numerics fingerprint, measured in a process of its own; a shipment from a client
    with that fingerprint is refused here, naming both differences, and the envelope of a
    campaign records this host's fingerprint."""
    import dataclasses

    from ogk.sil import numerics
    here = numerics.fingerprint()
    core = "Nehalem" if "Sandybridge" in here["blas"] else "Sandybridge"
    from numpy._core import _multiarray_umath as um
    simd = [t for t in here["numpy_simd"].split(",")      # a dispatched target, never baseline
            if t.startswith("X86_V") and t not in um.__cpu_baseline__][-1:]
    env = {**os.environ, "OPENBLAS_CORETYPE": core, "NPY_DISABLE_CPU_FEATURES": ",".join(simd)}
    out = subprocess.run([sys.executable, "-c", "import json; from ogk.sil.numerics import "
                          "fingerprint; print(json.dumps(fingerprint()))"],
                         env=env, capture_output=True, text=True, check=True)
    other = json.loads(out.stdout)
    assert core in other["blas"] and core not in here["blas"]
    # numpy refuses to disable its baseline: only a dispatched target (X86_V3 here) can go
    differ = ["blas", "numpy_simd"] if other["numpy_simd"] != here["numpy_simd"] else ["blas"]
    assert sorted(k for k in here if here[k] != other[k]) == differ
    plan = plan_of("low-thrust-transfer")
    shipment = shipping.ship(plan, family_object("low-thrust-transfer"))
    assert shipment.numerics == here
    assert shipping.plan_of(shipment).products == plan.products   # built and cached here
    with pytest.raises(OgkInputError, match="numerics differ.*blas"):  # refused all the same
        shipping.plan_of(dataclasses.replace(shipment, numerics=other))
    flown = fly_campaign(plan, 1, 3, workers=1, progress=False)
    assert envelope.envelope(flown)["numerics"] == here


@pytest.mark.req("OGK-HAR-017", "OGK-HAR-005")
def test_ogk_mc_dask_local_writes_the_local_table_and_bad_addresses_are_one_line(tmp_path, capsys):
    family = "low-thrust-transfer"
    scenario, _ = FAMILIES[family]
    out = tmp_path / "d.json"
    res = ogk("mc", scenario, "--runs", "2", "--seed", "3", "--dask", "local:1",
              *CLI_OPTIONS.get(family, []), "--json", str(out))
    assert res.returncode in (0, 1) and "Traceback" not in res.stderr, res.stdout + res.stderr
    doc = json.loads(out.read_text())
    assert doc["workers"] == 1 and doc["runs"] == 2
    local = fly_campaign(plan_of(family), 2, 3, workers=1, progress=False)
    rows = envelope.read_table(tmp_path / doc["per_run_table"])
    assert same(without_timing(rows), without_timing(local.records))
    for bad, key in ((["--dask", "local:0"], "--dask"), (["--dask", "nowhere"], "--dask"),
                     (["--dask", "local:2", "--workers", "2"], "--workers")):
        capsys.readouterr()
        code = main(["mc", scenario, "--runs", "2", *bad, "--json", str(tmp_path / "x.json")])
        err = capsys.readouterr().err
        assert code == 2 and len(err.strip().splitlines()) == 1 and key in err, err
