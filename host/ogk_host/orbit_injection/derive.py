"""Settings of an orbit-injection mission derived from its physics unless the scenario sets them.

`effective_settings(scn)` returns the values the tables and the SIL fly, each with its provenance
("scenario" = read from the file, "derived" = computed here by the documented rule):

- CPD gains (docs/design/cpd.md, "Design rule for another vehicle"; the re-derived set, flown unless
  `[cpd] flown = "printed"`, recorded as `cpd_flown`): the sec. 5.3 rule of the mission-independent
  ground tool (ogk_host.cpd_design: `VehicleModel.effectiveness` for G, `design_axis` for
  k_p = omega_n^2 / G_min, k_d = 2 zeta omega_n / G_min) applied to this scenario's vehicle at ignition,
  where l is smallest and I largest, so G_x = 1 / I_x0, G_y = T l0 / I_y0, G_z = T l0 / I_z0 are the
  G_min of each axis (T is the smallest thrust of the burn, T_min of sec. 7 eq. 57 for a tabulated
  thrust, the constant T = n0 m0 of sec. 6); pitch and yaw share one set designed on min(G_y, G_z).
  Taken from `[cpd.rederived]` when present.
- End-game freeze (docs/design/vtd-nog.md, "End-game"): freeze_time_to_go_s = Delta t_S / 4, the spacing of
  the paper's gain grid near cut-off (4 nodes per sampling interval; 0.5 s for Delta t_S = 2 s, the
  flown value: freezing earlier was measured to be worse, and the gain grid ends there). Taken from
  `guidance.end_game.freeze_time_to_go_s` when present. tau_freeze = freeze / t_f*.
- Braking accelerations of the CPD rate cap (docs/design/cpd.md): braking_margin times the smallest
  control acceleration at the command limits over the burn: roll M_xc / I_x0, pitch/yaw
  T l0 sin(Delta_c) / I_y0, I_z0. Always derived (the margin is the scenario's setting).

- What scales with the burn (docs/design/vtd-nog.md, "Derived settings"), from the nominal minimum time
  t_f* (`resolve(scn, t_f_star_s)`, called once where the scenario is loaded and its nominal
  known: `ogk tables`, the campaign plan; what flies takes the resolved scenario and only checks
  it, `require_resolved`), each the paper's mission's setting as a fraction of
  its 105.9 s burn: the |dt_f| clip dtf_max_s = 0.375 t_f* (40 s; the kernel requires <= t_f*/2),
  the fine-sampling window fine_window_s = 0.19 t_f* (20 s) and the terminal window
  terminal_window_s = 0.094 t_f* (10 s; at least terminal_shape_hold_s). The windows are derived
  only with the energy cut-off (the paper's end-game has none). Measured at the short-burn corner
  of the envelope (t_f* = 41.8 s, 200 runs, seed 777): a copied 10 s terminal window fails 18
  runs, 5 s fails 1 (docs/design/vtd-nog.md).
- The terminal stage's turn limit (docs/design/vtd-nog.md, "Terminal steering within the vehicle's turn
  rate"; kernel ogk_terminal_config_t.turn_accel_rad_s2): the angular acceleration the vehicle's TVC
  gives at its command limit, sin(Delta_c) T l(t) / I(t) (pitch and yaw, the smaller; T the smallest
  thrust, eq. 53's arm and inertias), the smallest over the terminal window [t_f* - window, t_f*]:
  the attitude loop turns the thrust direction no faster than that. The kernel bounds each shaped
  plan's tilt from the velocity to be gained to a S^2 / 16, S = window - hold. Measured: the paper's
  mission 0.273 rad/s^2 (bound 62 deg: no plan of 1000 runs reaches it), the section-7 upper stage
  19.9 (no bound below 1.5 rad), the short-burn corner 0.198 (2.6 deg: v_go steering; 52 -> 1
  failure in 1000 runs of seed 4242, radius sigma 1.5 km, velocities 30 m/s). The bound is necessary, not sufficient: the paper's
  10 s window copied onto that corner (bound 42 deg) still fails 8.6 % (docs/design/vtd-nog.md). Taken from
  `guidance.end_game.terminal_turn_accel_rad_s2` when present.
- The envelope (`envelope_warnings(scn, t_f_star_s)`): one line per setting outside what was
  measured to fly, naming its key: the nominal's envelope (R_f / perigee 1.5..8, n0 0.5..1.5 g0,
  c 2.5..4.5 km/s), a window or clip set above 2x its rule, and the initial-state dispersions
  beyond the linear domain of the neighbouring-optimal law (3 sigma of the radius above 0.2 n0
  t_f*^2, 3 sigma of a velocity component above 0.1 of the burn's Delta v; the paper's mission is
  at 0.12 and 0.062), each dispersion line with what was measured beyond it at the short-burn
  corner (`RADIUS_BEYOND_MEASURED`, `VELOCITY_BEYOND_MEASURED`; inside the domain that corner
  fails 0 of 1000 runs on two seeds).

Written against the scenario loader both before and after its keys became optional
(`getattr(..., None)`): a missing `[cpd.rederived]` is `scn.cpd.rederived is None`, a missing
freeze key is `scn.end_game.freeze_time_to_go_s is None`.
"""
from __future__ import annotations

import dataclasses
import math
import sys
from typing import Any

import numpy as np

from .. import cpd_design
from .scenario import CpdGains, OrbitInjectionScenario

SCENARIO = "scenario"
DERIVED = "derived"
#: Freeze rule: this fraction of the sampling interval (docs/design/vtd-nog.md, "End-game").
FREEZE_FRACTION_OF_SAMPLE = 0.25
#: Burn-scaled rules: the paper's mission's settings over its t_f* = 105.9 s (module docstring).
DTF_MAX_FRACTION_OF_BURN = 0.375
FINE_WINDOW_FRACTION_OF_BURN = 0.19
TERMINAL_WINDOW_FRACTION_OF_BURN = 0.094
#: A window or clip set above this multiple of its rule gets a warning.
WINDOW_WARNING_FACTOR = 2.0
#: Linear domain of VTD-NOG (module docstring): 3 sigma radius / (n0 t_f*^2), 3 sigma velocity / Delta v.
RADIUS_DISPERSION_FRACTION = 0.2
VELOCITY_DISPERSION_FRACTION = 0.1
#: What was measured beyond the linear domain, quoted by each warning (docs/design/vtd-nog.md, "Envelope
#: warnings"): the short-burn corner (R_f / r_p 1.5, 1.5 g0, 4.5 km/s, derived settings), 1000 runs,
#: 6-DOF, every dispersion, `ogk mc FILE --runs 1000 --seed S --workers 2`: radius 3 sigma at 0.29 n0
#: t_f*^2 (2.5 km, velocities 22 m/s) 15 failures (seed 83219); at 0.58 (the paper's 5 km, 30 m/s)
#: 200 (seed 83219); velocity 3 sigma at 0.136 of Delta v (30 m/s, radius 1.5 km) 1 and 2 (seeds 606032,
#: 711032); inside the domain (1.5 km, 20 m/s) 0 and 0 (the same seeds).
#: the paper's 10 s terminal and 20 s fine windows copied onto the corner (dispersions inside the
#: domain, 1.5 km / 20 m/s): 86 failures (seed 83219), against 0 with the rule's windows
WINDOW_BEYOND_MEASURED = ("measured at the short-burn corner: the paper's 10 s and 20 s windows copied "
                          "fail 8.6 % of 1000 runs inside the linear domain")
RADIUS_BEYOND_MEASURED = "measured at the short-burn corner, 1000 runs: 1.5 % fail at 0.29, 20 % at 0.58"
VELOCITY_BEYOND_MEASURED = ("measured at the short-burn corner, 1000 runs with the radius inside its "
                            "domain: 0.1-0.2 % fail at 0.136")
#: The nominal's envelope (docs/design/vtd-nog.md sec. 2): R_f / perigee, n0 [g0], c [m/s].
ENVELOPE_RADIUS_RATIO = (1.5, 8.0)
ENVELOPE_ACCEL_G0 = (0.5, 1.5)
ENVELOPE_EXHAUST_M_S = (2500.0, 4500.0)
EG_KEY = "guidance.end_game."
#: The terminal stage's turn limit (module docstring) and the samples of the window it is taken over.
TURN_ACCEL_KEY = "terminal_turn_accel_rad_s2"
TURN_ACCEL_SAMPLES = 201
G0 = 9.80665   #: standard gravity [m/s^2], for n0 in g0


@dataclasses.dataclass(frozen=True)
class EffectiveSettings:
    """What flies, with where each value came from (SCENARIO or DERIVED)."""

    cpd_gains: CpdGains
    cpd_gains_source: str
    freeze_time_to_go_s: float
    freeze_source: str
    braking_accels_rad_s2: tuple[float, float, float]   #: (roll, pitch, yaw)
    braking_source: str
    cpd_flown: str = "rederived"    #: the scenario's [cpd] flown: "printed" flies [cpd.printed] instead
    #: the burn-scaled end-game settings: key -> (value, source); empty until resolved with t_f*
    end_game: tuple[tuple[str, float, str], ...] = ()

    def tau_freeze(self, t_f_star_s: float) -> float:
        """ogk_nog_config_t.tau_freeze for the nominal minimum time t_f*."""
        return self.freeze_time_to_go_s / t_f_star_s

    def as_manifest(self) -> dict[str, Any]:
        """JSON-ready record (values SI) for the tables' manifest."""
        return {
            "cpd_gains": {"value": dataclasses.asdict(self.cpd_gains),
                          "source": self.cpd_gains_source, "flown": self.cpd_flown},
            "freeze_time_to_go_s": {"value": self.freeze_time_to_go_s,
                                    "source": self.freeze_source},
            "braking_accels_rad_s2": {"value": list(self.braking_accels_rad_s2),
                                      "source": self.braking_source},
            **{key: {"value": value, "source": source} for key, value, source in self.end_game},
        }


def vehicle(scn: OrbitInjectionScenario) -> cpd_design.VehicleModel:
    """The scenario's vehicle for the CPD design: its smallest thrust, eq. (53)'s arm and inertias."""
    mp = scn.mass_properties
    return cpd_design.VehicleModel(
        thrust_n=scn.thrust.min_thrust_n, arm0_m=mp.tvc_arm_m, arm_rate_m_s=mp.tvc_arm_rate_m_s,
        inertia0_kg_m2=(mp.inertia_x_kg_m2, mp.inertia_y_kg_m2, mp.inertia_z_kg_m2),
        inertia_rate_kg_m2_s=(mp.inertia_x_rate_kg_m2_s, mp.inertia_y_rate_kg_m2_s,
                              mp.inertia_z_rate_kg_m2_s),
        burn_time_s=0.0)   # only G at ignition is used


def design_rule_gains(scn: OrbitInjectionScenario) -> CpdGains:
    """Sec. 5.3 design rule (cpd_design.design_axis) with the scenario's omega_n, zeta and its G at
    ignition; one pitch/yaw set on the smaller of G_y, G_z."""
    w, z = scn.cpd.natural_frequency_rad_s, scn.cpd.damping_ratio
    g_x, g_y, g_z = (float(g) for g in vehicle(scn).effectiveness(0.0))
    g_yz = min(g_y, g_z)
    roll = cpd_design.design_axis(g_x, w, z)
    pitch_yaw = cpd_design.design_axis(g_yz, w, z)
    return CpdGains(gain_roll_g_per_kg_m2=g_x, gain_pitch_yaw_g_s2=g_yz,
                    kp_roll_n_m_per_rad=roll.k_p, kd_roll_n_m_s_per_rad=roll.k_d,
                    kp_pitch_yaw=pitch_yaw.k_p, kd_pitch_yaw_s=pitch_yaw.k_d)


def freeze_rule_s(scn: OrbitInjectionScenario) -> float:
    """Derived end-game freeze time: Delta t_S / 4 (0.5 s for the paper's 2 s)."""
    return FREEZE_FRACTION_OF_SAMPLE * scn.sample_interval_s


def braking_accels(scn: OrbitInjectionScenario) -> tuple[float, float, float]:
    """ogk_cpd_config_t.approach_accel_{x,y,z} [rad/s^2] (see the module docstring)."""
    cpd, mp, thrust_n = scn.cpd, scn.mass_properties, scn.thrust.min_thrust_n
    return (cpd.braking_margin * cpd.roll_torque_command_max_n_m / mp.inertia_x_kg_m2,
            cpd.braking_margin * thrust_n * mp.tvc_arm_m / mp.inertia_y_kg_m2
            * math.sin(cpd.deflection_y_command_max_rad),
            cpd.braking_margin * thrust_n * mp.tvc_arm_m / mp.inertia_z_kg_m2
            * math.sin(cpd.deflection_z_command_max_rad))


def effective_settings(scn: OrbitInjectionScenario,
                       t_f_star_s: float | None = None) -> EffectiveSettings:
    """The flown settings of `scn`, scenario values first, derived ones where the file is silent;
    with `t_f_star_s`, the burn-scaled end-game settings too."""
    stored = getattr(scn.cpd, "rederived", None)
    if stored is not None:
        gains, gains_src = stored, SCENARIO
    else:
        gains, gains_src = design_rule_gains(scn), DERIVED
    freeze = getattr(scn.end_game, "freeze_time_to_go_s", None)
    if freeze is not None:
        freeze_s, freeze_src = float(freeze), SCENARIO
    else:
        freeze_s, freeze_src = freeze_rule_s(scn), DERIVED
    return EffectiveSettings(cpd_gains=gains, cpd_gains_source=gains_src,
                             freeze_time_to_go_s=freeze_s, freeze_source=freeze_src,
                             braking_accels_rad_s2=braking_accels(scn), braking_source=DERIVED,
                             cpd_flown=str(getattr(scn.cpd, "flown", "rederived")),
                             end_game=(() if t_f_star_s is None
                                       else burn_scaled(scn, t_f_star_s)))


def burn_rules(scn: OrbitInjectionScenario, t_f_star_s: float) -> dict[str, float]:
    """The rule's dtf_max_s, fine_window_s and terminal_window_s [s] for a burn of t_f* (module docstring)."""
    return {"dtf_max_s": DTF_MAX_FRACTION_OF_BURN * t_f_star_s,
            "fine_window_s": FINE_WINDOW_FRACTION_OF_BURN * t_f_star_s,
            # the v_go hold is the window's last part: the window is never shorter
            "terminal_window_s": max(TERMINAL_WINDOW_FRACTION_OF_BURN * t_f_star_s,
                                     scn.end_game.terminal_shape_hold_s)}


def turn_accel_rule(scn: OrbitInjectionScenario, t_f_star_s: float, window_s: float) -> float:
    """The vehicle's angular acceleration at its TVC command limit [rad/s^2], the smallest over the
    terminal window [t_f* - window, t_f*] and over pitch and yaw (module docstring)."""
    t = np.linspace(max(0.0, t_f_star_s - window_s), t_f_star_s, TURN_ACCEL_SAMPLES)
    g = vehicle(scn).effectiveness(t)           # (G_x, G_y, G_z)(t), G_y = T l / I_y [1/s^2]
    cpd = scn.cpd
    return float(min(np.min(g[1]) * math.sin(cpd.deflection_y_command_max_rad),
                     np.min(g[2]) * math.sin(cpd.deflection_z_command_max_rad)))


def burn_scaled(scn: OrbitInjectionScenario, t_f_star_s: float) -> tuple[tuple[str, float, str], ...]:
    """(key, value, source) of dtf_max_s, fine_window_s, terminal_window_s and the terminal turn
    limit terminal_turn_accel_rad_s2 (over the window in force) for a burn of t_f*: the scenario's
    value where it sets one, else the rule's."""
    out = []
    for key, rule in burn_rules(scn, t_f_star_s).items():
        stored = getattr(scn.end_game, key)
        out.append((key, float(stored), SCENARIO) if stored is not None else (key, rule, DERIVED))
    window = next(value for key, value, _ in out if key == "terminal_window_s")
    stored = scn.end_game.terminal_turn_accel_rad_s2
    out.append((TURN_ACCEL_KEY, float(stored), SCENARIO) if stored is not None
               else (TURN_ACCEL_KEY, turn_accel_rule(scn, t_f_star_s, window), DERIVED))
    return tuple(out)


def resolve(scn: OrbitInjectionScenario, t_f_star_s: float) -> OrbitInjectionScenario:
    """`scn` with every burn-scaled end-game setting it leaves out derived for a burn of t_f*
    (a scenario that sets them all comes back unchanged)."""
    values = {key: value for key, value, _ in burn_scaled(scn, t_f_star_s)}
    if all(getattr(scn.end_game, key) == value for key, value in values.items()):
        return scn
    return dataclasses.replace(scn, end_game=dataclasses.replace(scn.end_game, **values))


#: The end-game settings `resolve` fills from t_f*: the windows and clip, and the turn limit
WINDOW_KEYS = ("dtf_max_s", "fine_window_s", "terminal_window_s")


def require_resolved(scn: OrbitInjectionScenario, keys: tuple[str, ...] = WINDOW_KEYS) -> None:
    """ValueError when a burn-scaled setting of `keys` is still unset (a caller skipped `resolve`);
    by default the windows and clip (the terminal stage's configuration also needs TURN_ACCEL_KEY)."""
    missing = [key for key in keys if getattr(scn.end_game, key) is None]
    if missing:
        raise ValueError(f"end-game settings {missing} not resolved: call derive.resolve(scn, t_f*)")


def delta_v_m_s(scn: OrbitInjectionScenario, t_f_star_s: float) -> float:
    """The nominal burn's Delta v: the integral of T/m over [0, t_f*] (trapezoid, 2001 points)."""
    t = np.linspace(0.0, t_f_star_s, 2001)
    a = np.asarray(scn.thrust.accel_m_s2(t), dtype=np.float64)
    return float(np.sum(0.5 * (a[1:] + a[:-1]) * np.diff(t)))


def envelope_warnings(scn: OrbitInjectionScenario, t_f_star_s: float) -> list[tuple[str, str]]:
    """(key, reason) for each setting outside the measured envelope (module docstring)."""
    out: list[tuple[str, str]] = []
    n0_g0 = scn.thrust.initial_accel_m_s2 / G0
    c = scn.thrust.exhaust_velocity_m_s
    if scn.pre_ignition is not None:   # the envelope is stated for the free-ignition ellipse (case B)
        perigee = scn.pre_ignition.semi_major_axis_m * (1.0 - scn.pre_ignition.eccentricity)
        ratio = scn.target_radius_m / perigee
        for key, value, (lo, hi), what in (
                ("target_orbit.radius_m", ratio, ENVELOPE_RADIUS_RATIO, "R_f / perigee"),
                ("thrust.initial_accel_g0", n0_g0, ENVELOPE_ACCEL_G0, "n0 [g0]"),
                ("thrust.exhaust_velocity_m_s", c, ENVELOPE_EXHAUST_M_S, "c [m/s]")):
            if not lo <= value <= hi:
                out.append((key, f"{what} = {value:.4g} is outside the envelope {lo:g}..{hi:g} "
                            f"where the nominal and its campaigns are verified"))
    rules = burn_rules(scn, t_f_star_s)
    for key, value, source in burn_scaled(scn, t_f_star_s):
        if key not in rules:       # the turn limit: vehicle data, no window rule
            continue
        rule = rules[key]
        if source == SCENARIO and value > WINDOW_WARNING_FACTOR * rule:
            out.append((EG_KEY + key, f"{value:g} s is {value / t_f_star_s:.0%} of this burn "
                        f"(t_f* = {t_f_star_s:.4g} s), above {WINDOW_WARNING_FACTOR:g}x the rule's "
                        f"{rule:.3g} s: leave the key out to fly the rule ({WINDOW_BEYOND_MEASURED})"))
    isd = scn.initial_state_dispersion
    radius_scale = scn.thrust.initial_accel_m_s2 * t_f_star_s ** 2
    if 3.0 * isd.radius_m > RADIUS_DISPERSION_FRACTION * radius_scale:
        out.append(("dispersions.initial_state.radius_m",
                    f"3 sigma = {3.0 * isd.radius_m:g} m is {3.0 * isd.radius_m / radius_scale:.2f} "
                    f"n0 t_f*^2, beyond the linear domain of VTD-NOG ({RADIUS_DISPERSION_FRACTION:g}; "
                    f"<= {RADIUS_DISPERSION_FRACTION * radius_scale / 3.0:.4g} m sigma for this burn; "
                    f"{RADIUS_BEYOND_MEASURED})"))
    dv = delta_v_m_s(scn, t_f_star_s)
    for name in ("radial_velocity_m_s", "transverse_velocity_m_s", "normal_velocity_m_s"):
        sigma = float(getattr(isd, name))
        if 3.0 * sigma > VELOCITY_DISPERSION_FRACTION * dv:
            out.append((f"dispersions.initial_state.{name}",
                        f"3 sigma = {3.0 * sigma:g} m/s is {3.0 * sigma / dv:.3f} of the burn's "
                        f"Delta v ({dv:.4g} m/s), beyond the linear domain of VTD-NOG "
                        f"({VELOCITY_DISPERSION_FRACTION:g}; <= {VELOCITY_DISPERSION_FRACTION * dv / 3.0:.3g} "
                        f"m/s sigma for this burn; {VELOCITY_BEYOND_MEASURED})"))
    return out


def warn_outside_envelope(scn: OrbitInjectionScenario, t_f_star_s: float) -> int:
    """One line on stderr per setting outside the measured envelope (envelope_warnings),
    FILE: KEY: warning: REASON; returns how many (`ogk tables` and `ogk mc` print them)."""
    found = envelope_warnings(scn, t_f_star_s)
    for key, reason in found:
        print(f"{scn.path}: {key}: warning: {reason}", file=sys.stderr)
    return len(found)
