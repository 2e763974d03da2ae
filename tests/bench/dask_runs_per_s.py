"""runs/s of the Dask executor, local:1 and local:2, per family (docs/guides/scale-out.md): one JSON line
per family and worker count. `.venv/bin/python tests/bench/dask_runs_per_s.py [FAMILY ...]`."""
import os, sys, time, json
from ogk_host.scenario_file import read_header, resolve_scenario
from ogk.missions import registry
from ogk.sil.engine import fly_campaign
from ogk.sil.dask_executor import DaskExecutor

CASES = {  # family: (scenario, options, runs, chunk_runs)
    "orbit-injection": ("leo-geo", {}, 1000, 250),   # the default chunk: flown vectorised
    "low-thrust-transfer": ("apophis", {}, 40, 10),
    "low-thrust-rendezvous": ("rendezvous_nep_min_time", {}, 4, 1),
    "binary-asteroid": ("moshup", {"perturbation": [10.0, 40.0]}, 16, 4),
}

def main():
    only = sys.argv[1:] or list(CASES)
    for fam_name in only:
        scn, opts, runs, chunk = CASES[fam_name]
        h = read_header(resolve_scenario(scn)); fam = registry.family(h)
        plan = fam.plan(h, dict(opts))
        for n in (1, 2):
            with DaskExecutor(f"local:{n}", fam) as ex:
                t0 = time.perf_counter()
                fly_campaign(plan, n, 1, chunk_runs=1, executor=ex, progress=False)   # plan rebuilt on each worker
                warm = time.perf_counter() - t0
                la0 = os.getloadavg()[0]
                f = fly_campaign(plan, runs, 2, chunk_runs=chunk, executor=ex, progress=False)
                la1 = os.getloadavg()[0]
            print(json.dumps({"family": fam_name, "workers": n, "runs": runs, "chunk_runs": chunk,
                              "warmup_s": round(warm, 1), "wall_s": round(f.wall_s, 2),
                              "runs_per_s": round(runs / f.wall_s, 3), "cpu_s_per_run": round(f.cpu_s / runs, 3),
                              "load": [round(la0, 1), round(la1, 1)]}), flush=True)

if __name__ == "__main__":
    main()
