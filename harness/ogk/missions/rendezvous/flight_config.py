"""Flight configuration of a rendezvous scenario as const C (docs/guides/flight-integration-nmpc.md).

What the NMPC flight program (port/cortex-m7/pil/nmpc_flight.c) needs, built by the same functions the
SIL's kernel guidance uses (kernel_guidance.kernel_config, guidance_base.first_guesses), handed to
ogk_host.cgen.write_c_config, so the header cannot drift from the SIL's configuration:

- `ogk_nmpc_flight_config`: the ogk_nmpc_config_t of the scenario and strategy;
- `ogk_nmpc_flight_guesses`: the first replan's open-loop guesses (the ground's documented guess at
  the GUESS_FACTORS), tried in turn; their node 0 and t0 are replaced by the measured state and time
  at the first replan, exactly as first_guesses does;
- defines: the guess count and the minimum-fuel throttle of the guess built from the minimum-time
  optimum (nlp.MIN_FUEL_GUESS_THROTTLE).

The guesses depend on the scenario only (phase_matched_guess of the vehicle and the transfer), not on
the measured state: a new mission needs nothing but its scenario file.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

HEADER = "ogk_nmpc_flight_config.h"


def flight_items(scenario: Any, strategy: str) -> tuple[Any, Any, Any, int]:
    """(ffi, config cdata, guesses cdata array, number of guesses) as KernelGuidance flies them, for
    the scenario as the campaign flies it (family.with_model: its predictive model's third bodies)."""
    from ogk_host.rendezvous.dynamics import Model

    from ogk_bindings._ffi import ffi

    from .guidance_base import first_guesses, strategy_settings
    from .kernel_guidance import kernel_config

    settings = strategy_settings(scenario, strategy)
    cfg = kernel_config(scenario, settings)
    nu = 1 if cfg.engine == 0 else 2
    model = Model.for_scenario(scenario)
    t0 = scenario.problem.start_time_s / model.units.time_s
    guesses = first_guesses(scenario, scenario.ocp.nodes, t0, model.x0, nu)
    arr = ffi.new(f"ogk_nmpc_plan_t[{len(guesses)}]")
    for i, g in enumerate(guesses):
        p = arr[i]
        p.t0 = float(g.t0)
        p.horizon = float(g.horizon)
        p.nodes = g.states.shape[0] - 1
        p.nu = nu
        for k, v in enumerate(g.states.reshape(-1)):
            p.x[k] = float(v)
        for k, v in enumerate(g.controls.reshape(-1)):
            p.u[k] = float(v)
    return ffi, cfg.to_c(), arr, len(guesses)


def write_flight_config(out: Path, scenario_path: Path, scenario: Any, strategy: str,
                        third_bodies: str) -> Path:
    """OUT/c/ogk_nmpc_flight_config.h for `scenario` (loaded from scenario_path, its predictive
    model's third bodies as the campaign's `third_bodies`: "scenario", "yes", "no") flown with
    `strategy`."""
    from ogk_host.cgen import ConfigItem, write_c_config
    from ogk_host.rendezvous.nlp import MIN_FUEL_GUESS_THROTTLE

    ffi, cfg, guesses, n = flight_items(scenario, strategy)
    from ogk.sil.pil_build import nmpc_single_precision_tolerances
    nmpc_single_precision_tolerances(cfg)   # floored for a float kernel (the M4F); as is otherwise
    return write_c_config(
        ffi, [ConfigItem("ogk_nmpc_flight_config", cfg,
                         f"ogk_nmpc (ogk/nmpc.h), strategy {strategy}, third bodies in the model: "
                         f"{third_bodies}; normalised units (docs/design/nmpc.md)"),
              ConfigItem("ogk_nmpc_flight_guesses", guesses,
                         "the first replan's guesses, tried in turn (t0 and node 0 replaced by the "
                         "measured time and state)")],
        out / "c" / HEADER, scenario_path, includes=("ogk/nmpc.h",),
        defines={"OGK_NMPC_FLIGHT_N_GUESSES": int(n),
                 "OGK_NMPC_FLIGHT_MIN_FUEL_THROTTLE": float(MIN_FUEL_GUESS_THROTTLE)},
        note=f"strategy {strategy}, third bodies {third_bodies}; {n} guesses.")

