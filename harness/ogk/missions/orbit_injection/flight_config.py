"""Flight configuration of an orbit-injection scenario as const C (docs/guides/flight-integration.md).

The configs are the typed kernel configurations the SIL itself flies (nog_guidance.nog_config,
attitude.cpd_config, cutoff.cutoff_config, terminal.terminal_config), handed to
ogk_host.cgen.write_c_config, so the header cannot drift from the SIL's configuration. The
scenario comes in loaded and resolved (nominal_ref.resolved_with_reference), the table decoded
once: nothing here reads the scenario file again (its path is the headers' provenance only).
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

from ogk_bindings.cpd import CpdConfig
from ogk_bindings.nog import NogConfig
from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

#: Attitude-control rate of the flight configuration (the SIL's default, docs/guides/sil.md).
CONTROL_RATE_HZ = 50.0


def flight_configs(scn: OrbitInjectionScenario, table: Any) -> tuple[NogConfig, CpdConfig]:
    """(nog_config, cpd_config) as the SIL builds them, from the resolved scenario and the
    decoded table (nog_guidance.load_table)."""
    from ogk.missions.orbit_injection.attitude import cpd_config
    from ogk.missions.orbit_injection.nog_guidance import nog_config

    return (nog_config(scn, table),
            CpdConfig(**cpd_config(scn, control_period_s=1.0 / CONTROL_RATE_HZ)))


def end_game_configs(scn: OrbitInjectionScenario, table: Any) -> tuple[list[tuple[str, Any, str]],
                                                                       dict[str, float | int]]:
    """The scenario's end-game as the SIL flies it (sil.EndGamePlan at CONTROL_RATE_HZ): NOG with
    the end-game's last sampling interval, the energy cut-off and the terminal stage configurations,
    and the schedule as defines (the PIL flight program, port/cortex-m7/pil/oi_flight.c)."""
    from ogk.missions.orbit_injection.cutoff import cutoff_config
    from ogk.missions.orbit_injection.nog_guidance import nog_config
    from ogk.missions.orbit_injection.sil import EndGamePlan, SilSettings
    from ogk.missions.orbit_injection.terminal import terminal_config

    dt = 1.0 / CONTROL_RATE_HZ
    plan = EndGamePlan.of(scn, SilSettings(control_rate_hz=CONTROL_RATE_HZ))
    ticks = round(scn.sample_interval_s / dt)
    fine = 0 if plan.fine_interval_s is None else round(plan.fine_interval_s / dt)
    items = [("ogk_flight_endgame_nog_config", nog_config(scn, table, plan.fine_interval_s),
              "VTD-NOG with the end-game's last sampling interval (eq. 32's terminating sample)"),
             ("ogk_flight_cutoff_config", cutoff_config(scn, dt),
              "energy cut-off (ogk/cutoff.h), stepped at the control rate"),
             ("ogk_flight_terminal_config", terminal_config(scn),
              "terminal steering (ogk/terminal.h) along the velocity to be gained")]
    defines: dict[str, float | int] = {
        "OGK_FLIGHT_CONTROL_RATE_HZ": CONTROL_RATE_HZ,
        "OGK_FLIGHT_TICKS_PER_SAMPLE": int(ticks),
        "OGK_FLIGHT_FINE_TICKS": int(fine),
        "OGK_FLIGHT_FINE_WINDOW_S": float(plan.fine_window_s),
        "OGK_FLIGHT_ENERGY_CUTOFF": int(plan.energy_cutoff),
        "OGK_FLIGHT_TERMINAL": int(plan.terminal_window_s > 0.0)}
    return items, defines


def plant_defines(scn: OrbitInjectionScenario, t_f_star_s: float) -> dict[str, float]:
    """Scenario constants of the flight app's point-mass plant (eqs. 3-6, sec. 6 thrust)."""
    return {"OGK_PLANT_MU_M3_S2": float(scn.mu_m3_s2),
            "OGK_PLANT_N0_M_S2": float(scn.thrust.initial_accel_m_s2),
            "OGK_PLANT_EXHAUST_VELOCITY_M_S": float(scn.thrust.exhaust_velocity_m_s),
            "OGK_PLANT_TARGET_RADIUS_M": float(scn.target_radius_m),
            "OGK_PLANT_T_F_STAR_S": float(t_f_star_s),
            "OGK_PLANT_CONTROL_RATE_HZ": CONTROL_RATE_HZ}


def write_flight_config(out: Path, scn: OrbitInjectionScenario, scenario_path: Path,
                        bundle: Path) -> list[Path]:
    """The configuration header and the flight app's plant header of the resolved scenario `scn`
    (loaded from `scenario_path`, named in the headers' provenance) flying the tables of `bundle`."""
    from ogk_bindings._ffi import ffi
    from ogk_host.cgen import ConfigItem, write_c_config

    from ogk.missions.orbit_injection.nog_guidance import load_table

    table = load_table(bundle)
    t_f_star_s = float(table.t_f_star_s)  # type: ignore[attr-defined]
    nog, cpd = flight_configs(scn, table)
    end_game, schedule = end_game_configs(scn, table)
    # cgen walks the C structs (to_c: copies; the configs keep the table they point to alive)
    cfg = write_c_config(
        ffi, [ConfigItem("ogk_flight_nog_config", nog.to_c(),
                         "VTD-NOG (ogk/nog.h): bind .view (ogk_nog_table_view, in place) or .table (ogk_nog_table_load), then ogk_nog_init"),
              ConfigItem("ogk_flight_cpd_config", cpd.to_c(),
                         f"CPD (ogk/cpd.h), ff_period_s = the {CONTROL_RATE_HZ:g} Hz control period"),
              *(ConfigItem(name, value.to_c(), what) for name, value, what in end_game)],
        out / "c" / "ogk_orbit_injection_flight_config.h", scenario_path,
        includes=("ogk/nog.h", "ogk/cpd.h", "ogk/cutoff.h", "ogk/terminal.h"), defines=schedule,
        note=f"Table: {bundle.name}, t_f* = {t_f_star_s:.17g} s. The first two fly the "
             "paper's end-game (flightapp); the end-game items and the schedule defines fly the "
             "scenario's (the PIL flight program).")
    plant = write_c_config(ffi, [], out / "c" / "ogk_sil_plant.h", scenario_path, includes=(),
                           defines=plant_defines(scn, t_f_star_s),
                           note="Test-plant constants of the flight app (not flight data).")
    return [cfg, plant]
