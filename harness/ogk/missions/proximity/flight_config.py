"""Flight configuration of a proximity-approach scenario as const C: what the NMPC flight program
(port/cortex-m7/pil/nmpc_flight.c, the rendezvous' own) needs to fly the second problem of the same
solver (ogk/ocp.h), taken from the context the SIL's kernel guidance flies (guidance.kernel_context,
after ogk_prox_init), so the header cannot drift from the SIL:

- `ogk_nmpc_flight_config`: the solver's ogk_nmpc_config_t as ogk_prox_init bound it;
- `ogk_nmpc_flight_model`: the problem's data (ogk_prox_model_t), `OGK_NMPC_FLIGHT_PROBLEM` its callback
  table (`ogk_prox_problem`): the flight software binds them with ogk_nmpc_init_problem;
- `ogk_nmpc_flight_guesses`: one guess, the ground's plan (guidance.ground_plan) that KernelGuidance
  loads; the first replan puts the measured time and state in its node 0 and solves from it, which
  is the SIL's load-then-solve to the bit (the solve re-anchors node 0 and t0 at the measurement);
- `OGK_NMPC_FLIGHT_PRESOLVE 0`: no minimum-time pre-solve (the ground plan is the minimum-fuel one);
- with [guidance] fixed_final_time, `OGK_NMPC_FLIGHT_FINAL_TIME` (the ground plan's t_f), its band, the
  retries' first BFGS scale and the first plan's continuation steps: the flight program keeps that
  final time as KernelGuidance does.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

HEADER = "ogk_nmpc_flight_config.h"


def write_flight_config(out: Path, scenario_path: Path, scenario: Any, first: Any) -> Path:
    """OUT/c/ogk_nmpc_flight_config.h for `scenario` (loaded from scenario_path) with the ground plan
    `first` (guidance.Plan, normalised)."""
    from ogk_host.cgen import ConfigItem, write_c_config

    from ogk_bindings._ffi import ffi

    from .guidance import FIRST_SOLVE_STEPS, FIXED_T_F_BAND, RETRY_HESSIAN_INIT, kernel_context

    ctx = kernel_context(scenario)._ctx
    cfg = ffi.new("ogk_nmpc_config_t *", ctx.nmpc.cfg)
    from ogk.sil.pil_build import nmpc_single_precision_tolerances
    nmpc_single_precision_tolerances(cfg)   # floored for a float kernel (the M4F); as is otherwise
    model = ffi.new("ogk_prox_model_t *", ctx.model)
    guesses = ffi.new("ogk_nmpc_plan_t[1]")
    g = guesses[0]
    g.t0, g.horizon, g.nodes, g.nu = float(first.t0), float(first.horizon), int(first.nodes), 2
    for k, v in enumerate(first.states.reshape(-1)):
        g.x[k] = float(v)
    for k, v in enumerate(first.controls.reshape(-1)):
        g.u[k] = float(v)
    defines: dict[str, float | int | str] = {
        "OGK_NMPC_FLIGHT_N_GUESSES": 1, "OGK_NMPC_FLIGHT_MIN_FUEL_THROTTLE": 1.0,
        "OGK_NMPC_FLIGHT_PRESOLVE": 0, "OGK_NMPC_FLIGHT_PROBLEM": "(&ogk_prox_problem)",
        "OGK_NMPC_FLIGHT_MODEL_T": "ogk_prox_model_t"}
    if scenario.guidance.fixed_final_time:
        defines.update({"OGK_NMPC_FLIGHT_FINAL_TIME": float(first.t0) + float(first.horizon),
                        "OGK_NMPC_FLIGHT_FINAL_TIME_BAND": final_time_band(),
                        "OGK_NMPC_FLIGHT_RETRY_HESSIAN_INIT": RETRY_HESSIAN_INIT,
                        "OGK_NMPC_FLIGHT_FIRST_SOLVE_STEPS": f"{FIRST_SOLVE_STEPS}u"})
    return write_c_config(
        ffi, [ConfigItem("ogk_nmpc_flight_config", cfg,
                         "the solver's settings as ogk_prox_init binds them (ogk/nmpc.h; normalised units)"),
              ConfigItem("ogk_nmpc_flight_model", model,
                         "the proximity problem's data (ogk/proximity.h): LU = 1 km, TU = 1 / n, MU = [guidance] mass_unit_kg"),
              ConfigItem("ogk_nmpc_flight_guesses", guesses,
                         "the ground's plan (t0 and node 0 replaced by the measured time and state)")],
        out / "c" / HEADER, scenario_path, includes=("ogk/nmpc.h", "ogk/proximity.h"),
        defines=defines,
        note="the proximity approach on the NMPC flight program (ogk_nmpc_init_problem); 1 guess.")


def final_time_band() -> float:
    """The relative band the fixed final time is kept in (guidance.FIXED_T_F_BAND, 1e-9); on a
    single-precision kernel 8 eps of binary32 (9.5e-7): 1 +- 1e-9 rounds to 1 in binary32, the bounds
    would collapse onto the remaining time itself."""
    from ogk_host.cgen import current_precision

    from ogk.sil.precision import SINGLE_EPS
    from .guidance import FIXED_T_F_BAND
    return FIXED_T_F_BAND if current_precision() != "single" else max(FIXED_T_F_BAND, 8 * SINGLE_EPS)
