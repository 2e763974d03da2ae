"""Settings of an orbit-injection mission derived from its physics unless the scenario sets them.

`effective_settings(scn)` returns the values the tables and the SIL fly, each with its provenance
("scenario" = read from the file, "derived" = computed here by the documented rule):

- CPD gains (docs/cpd.md, "Design rule for another vehicle"; the re-derived set, flown unless
  `[cpd] flown = "printed"`, recorded as `cpd_flown`): the sec. 5.3 rule of the mission-independent
  ground tool (ogk_host.cpd_design: `VehicleModel.effectiveness` for G, `design_axis` for
  k_p = omega_n^2 / G_min, k_d = 2 zeta omega_n / G_min) applied to this scenario's vehicle at ignition,
  where l is smallest and I largest, so G_x = 1 / I_x0, G_y = T l0 / I_y0, G_z = T l0 / I_z0 are the
  G_min of each axis (T is the smallest thrust of the burn, T_min of sec. 7 eq. 57 for a tabulated
  thrust, the constant T = n0 m0 of sec. 6); pitch and yaw share one set designed on min(G_y, G_z).
  Taken from `[cpd.rederived]` when present.
- End-game freeze (docs/vtd-nog.md, "End-game"): freeze_time_to_go_s = Delta t_S / 4, the spacing of
  the paper's gain grid near cut-off (4 nodes per sampling interval; 0.5 s for Delta t_S = 2 s, the
  flown value: freezing earlier was measured to be worse, and the gain grid ends there). Taken from
  `guidance.end_game.freeze_time_to_go_s` when present. tau_freeze = freeze / t_f*.
- Braking accelerations of the CPD rate cap (docs/cpd.md): braking_margin times the smallest
  control acceleration at the command limits over the burn: roll M_xc / I_x0, pitch/yaw
  T l0 sin(Delta_c) / I_y0, I_z0. Always derived (the margin is the scenario's setting).

Written against the scenario loader both before and after its keys became optional
(`getattr(..., None)`): a missing `[cpd.rederived]` is `scn.cpd.rederived is None`, a missing
freeze key is `scn.end_game.freeze_time_to_go_s is None`.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

from .. import cpd_design
from .scenario import CpdGains, OrbitInjectionScenario

SCENARIO = "scenario"
DERIVED = "derived"
#: Freeze rule: this fraction of the sampling interval (docs/vtd-nog.md, "End-game").
FREEZE_FRACTION_OF_SAMPLE = 0.25


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


def effective_settings(scn: OrbitInjectionScenario) -> EffectiveSettings:
    """The flown settings of `scn`, scenario values first, derived ones where the file is silent."""
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
                             cpd_flown=str(getattr(scn.cpd, "flown", "rederived")))
