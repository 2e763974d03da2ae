"""CPD attitude-control gain design (Pontani & Celani 2021, sec. 5.3) and the loop figures behind
the choice of gains (docs/design/cpd.md).

Sec. 5.3 rule, per axis: with the control effectiveness G (G_x = 1 / I_x for the roll torque,
G_y = T l / I_y and G_z = T l / I_z for the TVC deflections) varying over the burn between G_min and
G_max, the gains

    k_p = omega_n^2 / G_min,     k_d = 2 zeta omega_n / G_min

give the loop of eq. (48), s^2 + G k_d s + G k_p, natural frequency
omega_n sqrt(G / G_min) >= omega_n and damping zeta sqrt(G / G_min) >= zeta for every G >= G_min. l(t) and I(t) follow eq. (53) and
T = n0 m0 is constant (sec. 6).

The analysis adds what eq. (48) leaves out: the first-order actuator (eqs. 16, 18; closed loop
tau s^3 + s^2 + G k_d s + G k_p), its phase margin, the width of the linear (unsaturated) band of
CPD, and the longest zero-order-hold control period that keeps the sampled loop stable.

It also runs the attitude-capture study behind the pointing-mode decision: the flight CPD (through
the cffi bindings) on the rigid-body dynamics of eqs. (13)-(18) with the initial attitude and rate
dispersions of Table 4, pitch/yaw error measured from the truth direction cosines.

    .venv/bin/python -m ogk_host.cpd_design              # gain and loop figures (docs/design/cpd.md)
    .venv/bin/python -m ogk_host.cpd_design --capture 200  # + capture study (~3 min)

(--capture also runs a numpy prototype of the same law, as a cross-check of the kernel, and of the
rate-capped proportional term discussed in docs/design/cpd.md; those prototypes are study code only.)
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import expm
from scipy.optimize import brentq

from .paths import SCENARIO_DIR

F64 = NDArray[np.float64]

STANDARD_GRAVITY_M_S2 = 9.80665
LEO_GEO_SCENARIO = SCENARIO_DIR / "leo_geo.toml"

#: Sec. 6 design targets: omega_n >= 4.24 rad/s, zeta >= 0.707 on every axis.
PAPER_OMEGA_N_RAD_S = 4.24
PAPER_ZETA = 0.707
#: Eq. (54) as printed (G_y is inconsistent with T l0 / I_y0, see seeds/README.md errata).
PRINTED_G_X = 8.33e-4
PRINTED_G_Y = 0.83
#: Gains printed after eq. (54).
PRINTED_GAINS = {"k_px": 21.6e3, "k_dx": 7.2e3, "k_py": 21.6, "k_dy": 7.20,
                 "k_pz": 21.6, "k_dz": 7.20}


# ----------------------------------------------------------------- vehicle
@dataclasses.dataclass(frozen=True)
class VehicleModel:
    """Constant thrust and the linear mass-property model of eq. (53)."""

    thrust_n: float                                   #: T [N]
    arm0_m: float                                     #: l0, centre of mass to TVC swivel [m]
    arm_rate_m_s: float                               #: ldot [m/s]
    inertia0_kg_m2: tuple[float, float, float]        #: (I_x0, I_y0, I_z0) [kg m^2]
    inertia_rate_kg_m2_s: tuple[float, float, float]  #: (Idot_x, Idot_y, Idot_z) [kg m^2/s]
    burn_time_s: float                                #: duration of the burn [s]

    def arm_m(self, t_s: F64 | float) -> F64:
        """l(t) = l0 + ldot t [m]."""
        return self.arm0_m + self.arm_rate_m_s * np.asarray(t_s, dtype=np.float64)

    def inertia_kg_m2(self, t_s: F64 | float) -> F64:
        """(I_x, I_y, I_z)(t), shape (3, *t.shape) [kg m^2]."""
        t = np.asarray(t_s, dtype=np.float64)
        i0 = np.asarray(self.inertia0_kg_m2).reshape((3,) + (1,) * t.ndim)
        idot = np.asarray(self.inertia_rate_kg_m2_s).reshape((3,) + (1,) * t.ndim)
        return i0 + idot * t

    def effectiveness(self, t_s: F64 | float) -> F64:
        """(G_x [1/(kg m^2)], G_y [1/s^2], G_z [1/s^2])(t), shape (3, *t.shape).

        G_x: roll acceleration per N m; G_y, G_z: pitch/yaw acceleration per rad of deflection."""
        inertia = self.inertia_kg_m2(t_s)
        torque_per_rad = self.thrust_n * self.arm_m(t_s)
        return np.stack([1.0 / inertia[0], torque_per_rad / inertia[1],
                         torque_per_rad / inertia[2]])


def leo_geo_vehicle(burn_time_s: float = 105.9,
                    standard_gravity_m_s2: float = STANDARD_GRAVITY_M_S2) -> VehicleModel:
    """LEO-to-GEO vehicle of sec. 6 / Table 1: T = n0 m0, n0 = 1.112 g, m0 = 2400 kg."""
    return VehicleModel(
        thrust_n=1.112 * standard_gravity_m_s2 * 2400.0,
        arm0_m=0.25, arm_rate_m_s=2.4e-3,
        inertia0_kg_m2=(1200.0, 800.0, 800.0),
        inertia_rate_kg_m2_s=(-4.36, -2.91, -2.91),
        burn_time_s=burn_time_s,
    )


def vehicle_from_scenario(path: Path = LEO_GEO_SCENARIO,
                          burn_time_s: float = 105.9) -> VehicleModel:
    """The same model from a scenario file's [thrust] and [mass_properties] tables."""
    with open(path, "rb") as fh:
        sc = tomllib.load(fh)
    th, mp = sc["thrust"], sc["mass_properties"]
    return VehicleModel(
        thrust_n=th["initial_accel_g0"] * th["standard_gravity_m_s2"] * th["initial_mass_kg"],
        arm0_m=mp["tvc_arm_m"], arm_rate_m_s=mp["tvc_arm_rate_m_s"],
        inertia0_kg_m2=(mp["inertia_x_kg_m2"], mp["inertia_y_kg_m2"], mp["inertia_z_kg_m2"]),
        inertia_rate_kg_m2_s=(mp["inertia_x_rate_kg_m2_s"], mp["inertia_y_rate_kg_m2_s"],
                              mp["inertia_z_rate_kg_m2_s"]),
        burn_time_s=burn_time_s,
    )


# ----------------------------------------------------------------- gain design
@dataclasses.dataclass(frozen=True)
class AxisGains:
    """Gains of one axis and the effectiveness range they were designed for."""

    k_p: float              #: [N m/rad] (roll) or [rad/rad] (pitch, yaw)
    k_d: float              #: [N m s/rad] (roll) or [s] (pitch, yaw)
    g_min: float            #: design (smallest) effectiveness
    g_max: float            #: largest effectiveness over the burn (nan if unknown)
    omega_n_min: float      #: [rad/s] natural frequency at g_min
    zeta_min: float         #: [-] damping at g_min

    def omega_n(self, g: F64 | float) -> F64:
        """Natural frequency of eq. (48) at effectiveness g [rad/s]."""
        return np.sqrt(np.asarray(g, dtype=np.float64) * self.k_p)

    def zeta(self, g: F64 | float) -> F64:
        """Damping ratio of eq. (48) at effectiveness g [-]."""
        g = np.asarray(g, dtype=np.float64)
        return g * self.k_d / (2.0 * np.sqrt(g * self.k_p))


def design_axis(g_min: float, omega_n: float, zeta: float, g_max: float = math.nan) -> AxisGains:
    """Sec. 5.3: k_p = omega_n^2 / G_min, k_d = 2 zeta omega_n / G_min."""
    if not (g_min > 0.0 and omega_n > 0.0 and zeta > 0.0):
        raise ValueError(f"need g_min, omega_n, zeta > 0, got {g_min}, {omega_n}, {zeta}")
    return AxisGains(k_p=omega_n**2 / g_min, k_d=2.0 * zeta * omega_n / g_min, g_min=g_min,
                     g_max=g_max, omega_n_min=omega_n, zeta_min=zeta)


@dataclasses.dataclass(frozen=True)
class CpdGains:
    """Gains of the three axes (roll x, pitch y, yaw z)."""

    roll: AxisGains
    pitch: AxisGains
    yaw: AxisGains

    def as_config_dict(self) -> dict[str, float]:
        """k_px ... k_dz, the names of ogk_cpd_config_t."""
        return {"k_px": self.roll.k_p, "k_dx": self.roll.k_d, "k_py": self.pitch.k_p,
                "k_dy": self.pitch.k_d, "k_pz": self.yaw.k_p, "k_dz": self.yaw.k_d}


def effectiveness_range(vehicle: VehicleModel, n_samples: int = 2001) -> tuple[F64, F64]:
    """(G_min, G_max) per axis over t in [0, burn_time], each shape (3,)."""
    g = vehicle.effectiveness(np.linspace(0.0, vehicle.burn_time_s, n_samples))
    return g.min(axis=1), g.max(axis=1)


def design_gains(vehicle: VehicleModel, omega_n: float = PAPER_OMEGA_N_RAD_S,
                 zeta: float = PAPER_ZETA) -> CpdGains:
    """Sec. 5.3 on all three axes, with G(t) from eq. (53) sampled over the burn."""
    g_min, g_max = effectiveness_range(vehicle)
    axes = [design_axis(float(g_min[i]), omega_n, zeta, float(g_max[i])) for i in range(3)]
    return CpdGains(roll=axes[0], pitch=axes[1], yaw=axes[2])


def printed_design(omega_n: float = PAPER_OMEGA_N_RAD_S, zeta: float = PAPER_ZETA) -> CpdGains:
    """Sec. 5.3 applied to eq. (54)'s printed G_x = 8.33e-4, G_y = G_z = 0.83 s^-2."""
    roll = design_axis(PRINTED_G_X, omega_n, zeta)
    pitch = design_axis(PRINTED_G_Y, omega_n, zeta)
    return CpdGains(roll=roll, pitch=pitch, yaw=pitch)


def printed_gains() -> CpdGains:
    """The gains exactly as printed after eq. (54) (k_p, k_d), with the printed G as g_min."""
    roll = AxisGains(PRINTED_GAINS["k_px"], PRINTED_GAINS["k_dx"], PRINTED_G_X, math.nan,
                     PAPER_OMEGA_N_RAD_S, PAPER_ZETA)
    pitch = AxisGains(PRINTED_GAINS["k_py"], PRINTED_GAINS["k_dy"], PRINTED_G_Y, math.nan,
                      PAPER_OMEGA_N_RAD_S, PAPER_ZETA)
    return CpdGains(roll=roll, pitch=pitch, yaw=pitch)


# ----------------------------------------------------------------- loop analysis
def second_order_poles(g: float, k_p: float, k_d: float) -> NDArray[np.complex128]:
    """Poles of eq. (48): s^2 + G k_d s + G k_p."""
    return np.roots([1.0, g * k_d, g * k_p]).astype(np.complex128)


def actuator_loop_poles(g: float, k_p: float, k_d: float, tau: float) -> NDArray[np.complex128]:
    """Poles with the first-order actuator (eqs. 42-44): tau s^3 + s^2 + G k_d s + G k_p."""
    return np.roots([tau, 1.0, g * k_d, g * k_p]).astype(np.complex128)


def open_loop(g: float, k_p: float, k_d: float, tau: float,
              omega: F64 | float) -> NDArray[np.complex128]:
    """L(j omega) = G (k_p + k_d s) / (s^2 (tau s + 1)), s = j omega."""
    s = 1j * np.asarray(omega, dtype=np.float64)
    return g * (k_p + k_d * s) / (s**2 * (tau * s + 1.0))


def phase_margin(g: float, k_p: float, k_d: float, tau: float) -> tuple[float, float]:
    """(gain-crossover frequency [rad/s], phase margin [deg]) of the continuous loop."""
    def log_mag(w: float) -> float:
        return float(np.log(np.abs(open_loop(g, k_p, k_d, tau, w))))
    wc = brentq(log_mag, 1e-6, 1e6, xtol=1e-12, rtol=1e-12)
    pm = 180.0 + math.degrees(float(np.angle(open_loop(g, k_p, k_d, tau, wc))))
    return float(wc), pm


def sampled_loop_matrix(g: float, k_p: float, k_d: float, tau: float, period: float) -> F64:
    """Transition matrix over one control period of [angle error, rate, actuator] with the PD
    command computed at the sample and held (zero-order hold, no saturation)."""
    a = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, g], [0.0, 0.0, -1.0 / tau]])
    b = np.array([0.0, 0.0, 1.0 / tau])
    # augmented exponential gives the ZOH input matrix exactly
    m = np.zeros((4, 4))
    m[:3, :3] = a * period
    m[:3, 3] = b * period
    em = expm(m)
    ad, bd = em[:3, :3], em[:3, 3]
    k = np.array([k_p, k_d, 0.0])      # u = -k_p e - k_d rate (e = angle - command)
    return ad - np.outer(bd, k)


def sampled_spectral_radius(g: float, k_p: float, k_d: float, tau: float, period: float) -> float:
    """Largest |eigenvalue| of sampled_loop_matrix (< 1: the sampled loop is stable)."""
    return float(np.max(np.abs(np.linalg.eigvals(sampled_loop_matrix(g, k_p, k_d, tau, period)))))


def max_stable_period(g: float, k_p: float, k_d: float, tau: float) -> float:
    """Longest control period [s] for which the sampled linear loop is stable (bisection)."""
    lo, hi = 1e-6, 2.0
    if sampled_spectral_radius(g, k_p, k_d, tau, hi) < 1.0:
        return hi
    for _ in range(80):
        mid = math.sqrt(lo * hi)
        if sampled_spectral_radius(g, k_p, k_d, tau, mid) < 1.0:
            lo = mid
        else:
            hi = mid
    return lo


@dataclasses.dataclass(frozen=True)
class LoopFigures:
    """One axis with one gain set, over the effectiveness samples g."""

    g: F64                      #: effectiveness samples
    omega_n: F64                #: [rad/s] eq. (48)
    zeta: F64                   #: [-] eq. (48)
    slowest_pole: F64           #: [rad/s] smallest |Re| of the poles with the actuator
    fastest_pole: F64           #: [rad/s] largest |pole| with the actuator
    min_pole_damping: F64       #: [-] smallest -Re/|p| of the poles with the actuator
    crossover: F64              #: [rad/s] gain crossover with the actuator
    phase_margin_deg: F64       #: [deg] with the actuator
    max_period_s: F64           #: [s] longest stable ZOH control period
    linear_error_band: float    #: limit / k_p [rad]: larger errors saturate (zero rate)
    linear_rate_band: float     #: limit / k_d [rad/s]: larger rates saturate (zero error)
    saturated_accel: F64        #: G * limit [rad/s^2]: the most the saturated command gives


def analyse_axis(gains: AxisGains, g: F64, tau: float, limit: float) -> LoopFigures:
    """Loop figures of one axis for effectiveness samples g, actuator tau and command limit."""
    g = np.asarray(g, dtype=np.float64)
    poles = np.array([actuator_loop_poles(gi, gains.k_p, gains.k_d, tau) for gi in g])
    margins = np.array([phase_margin(gi, gains.k_p, gains.k_d, tau) for gi in g])
    return LoopFigures(
        g=g, omega_n=gains.omega_n(g), zeta=gains.zeta(g),
        slowest_pole=np.min(-poles.real, axis=1),
        fastest_pole=np.max(np.abs(poles), axis=1),
        min_pole_damping=np.min(-poles.real / np.abs(poles), axis=1),
        crossover=margins[:, 0], phase_margin_deg=margins[:, 1],
        max_period_s=np.array([max_stable_period(gi, gains.k_p, gains.k_d, tau) for gi in g]),
        linear_error_band=limit / gains.k_p, linear_rate_band=limit / gains.k_d,
        saturated_accel=g * limit,
    )


# ----------------------------------------------------------------- report
def _report_axis(name: str, fig: LoopFigures, angle_unit: float, unit: str) -> list[str]:
    lines = [f"  {name}: G = {fig.g[0]:.4g} .. {fig.g[-1]:.4g}"]
    lines.append(f"    eq.48 omega_n {fig.omega_n[0]:.2f} .. {fig.omega_n[-1]:.2f} rad/s, "
                 f"zeta {fig.zeta[0]:.2f} .. {fig.zeta[-1]:.2f}")
    lines.append(f"    with actuator: slowest pole {fig.slowest_pole.min():.2f} rad/s, fastest "
                 f"{fig.fastest_pole.max():.1f} rad/s, min pole damping "
                 f"{fig.min_pole_damping.min():.2f}")
    lines.append(f"    crossover {fig.crossover[0]:.1f} .. {fig.crossover[-1]:.1f} rad/s, phase "
                 f"margin {fig.phase_margin_deg.min():.1f} .. {fig.phase_margin_deg.max():.1f} deg")
    lines.append(f"    longest stable control period {1e3 * fig.max_period_s.min():.1f} ms "
                 f"({1.0 / fig.max_period_s.min():.0f} Hz minimum rate)")
    lines.append(f"    linear band: error {fig.linear_error_band / angle_unit:.4f} {unit}, rate "
                 f"{fig.linear_rate_band / angle_unit:.4f} {unit}/s; saturated accel "
                 f"{math.degrees(fig.saturated_accel[0]):.2f} .. "
                 f"{math.degrees(fig.saturated_accel[-1]):.2f} deg/s^2")
    return lines


def report(vehicle: VehicleModel | None = None, tau: float = 0.1, m_xc_max: float = 30.0,
           delta_c_max: float = math.radians(0.65), n_g: int = 11) -> str:
    """Text report of both gain sets on the true effectiveness range (docs/design/cpd.md)."""
    vehicle = vehicle or leo_geo_vehicle()
    g_min, g_max = effectiveness_range(vehicle)
    rederived = design_gains(vehicle)
    printed = printed_gains()
    lines = [f"T = {vehicle.thrust_n:.2f} N, burn {vehicle.burn_time_s} s; "
             f"G_x {g_min[0]:.4e} .. {g_max[0]:.4e} 1/(kg m^2), "
             f"G_y {g_min[1]:.4f} .. {g_max[1]:.4f} 1/s^2 (printed: {PRINTED_G_Y})",
             f"printed design (G_y = {PRINTED_G_Y}): " + ", ".join(
                 f"{k} = {v:.4g}" for k, v in printed_design().as_config_dict().items()),
             "printed gains:   " + ", ".join(
                 f"{k} = {v:.4g}" for k, v in printed.as_config_dict().items()),
             "re-derived:      " + ", ".join(
                 f"{k} = {v:.4g}" for k, v in rederived.as_config_dict().items())]
    for label, gains in (("PRINTED gains on the true G", printed),
                         ("RE-DERIVED gains on the true G", rederived)):
        lines.append(label)
        g_roll = np.linspace(g_min[0], g_max[0], n_g)
        g_tvc = np.linspace(g_min[1], g_max[1], n_g)
        lines += _report_axis("roll ", analyse_axis(gains.roll, g_roll, tau, m_xc_max),
                              math.radians(1.0), "deg")
        lines += _report_axis("pitch/yaw", analyse_axis(gains.pitch, g_tvc, tau, delta_c_max),
                              math.radians(1.0), "deg")
    return "\n".join(lines)


# ----------------------------------------------------------------- attitude capture study
R_A = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])  #: rows a1, a2, a3 in c


def _euler_dcm(psi: F64, theta: F64, phi: F64) -> F64:
    """Body-from-a DCM R1(phi) R2(theta) R3(psi) (eq. 9), shape (N, 3, 3)."""
    cps, sps, cth, sth, cph, sph = (np.cos(psi), np.sin(psi), np.cos(theta), np.sin(theta),
                                    np.cos(phi), np.sin(phi))
    return np.stack([
        np.stack([cth * cps, cth * sps, -sth], -1),
        np.stack([sph * sth * cps - cph * sps, sph * sth * sps + cph * cps, sph * cth], -1),
        np.stack([cph * sth * cps + sph * sps, cph * sth * sps - sph * cps, cph * cth], -1),
    ], -2)


def _dcm_euler(c: F64) -> tuple[F64, F64, F64]:
    """(psi, theta, phi) of a body-from-a DCM (inverse of _euler_dcm)."""
    return (np.arctan2(c[:, 0, 1], c[:, 0, 0]), np.arcsin(np.clip(-c[:, 0, 2], -1.0, 1.0)),
            np.arctan2(c[:, 1, 2], c[:, 2, 2]))


@dataclasses.dataclass(frozen=True)
class CaptureResult:
    """Per-draw outcome of the capture study (one pointing mode, one gain set)."""

    pointing: str
    final_error_deg: F64        #: pointing error x_b -> T_c at the end [deg]
    max_error_deg: F64          #: largest pointing error [deg]
    capture_time_s: F64         #: first time after which the error stays below 1 deg (inf: never)
    duration_s: float

    @property
    def lost(self) -> NDArray[np.bool_]:
        """Draws that did not capture within the duration."""
        return ~np.isfinite(self.capture_time_s)


def prototype_body_cpd(c_bc: F64, rates: F64, t_c: F64, gains: CpdGains, limits: F64,
                       shaping_eta: float | None = None,
                       a_sat: tuple[float, float] = (math.nan, math.nan)) -> F64:
    """STUDY PROTOTYPE (numpy, not flight code): CPD with body-axis pointing, vectorised over draws,
    optionally with the proportional term capped as a rate command (docs/design/cpd.md):
    k_p e -> k_d sign(e) min((k_p / k_d) |e|, sqrt(2 eta a_sat |e|)), a_sat = (roll, pitch/yaw)
    saturated acceleration [rad/s^2]. shaping_eta None: the plain CPD law of the kernel.
    c_bc (N, 3, 3) body-from-c DCMs, rates (N, 3), t_c (3,) commanded direction in c; roll
    command 0.
    Returns (N, 3) commands (M_xc, D_yc, D_zc)."""
    t_b = c_bc @ t_c
    lateral = np.hypot(t_b[:, 1], t_b[:, 2])
    angle = np.arctan2(lateral, t_b[:, 0])
    scale = np.where(lateral > 0.0, angle / np.maximum(lateral, 1e-300), 1.0)
    e_y, e_z = -t_b[:, 2] * scale, t_b[:, 1] * scale
    c_ba = c_bc @ R_A.T
    e_x = -np.arctan2(c_ba[:, 1, 2], c_ba[:, 2, 2])        # wrap(0 - Phi)
    p_x, p_y, p_z = gains.roll.k_p * e_x, gains.pitch.k_p * e_y, gains.yaw.k_p * e_z
    if shaping_eta is not None:
        def rate_cmd(k_p: float, k_d: float, mag: F64, acc: float) -> F64:
            return np.minimum((k_p / k_d) * mag, np.sqrt(2.0 * shaping_eta * acc * mag))
        p_x = gains.roll.k_d * np.sign(e_x) * rate_cmd(gains.roll.k_p, gains.roll.k_d,
                                                       np.abs(e_x), a_sat[0])
        mag = np.hypot(e_y, e_z)
        factor = np.where(mag > 0.0, rate_cmd(gains.pitch.k_p, gains.pitch.k_d, mag, a_sat[1])
                          / np.maximum(mag, 1e-300), 0.0)
        p_y, p_z = gains.pitch.k_d * factor * e_y, gains.yaw.k_d * factor * e_z
    return np.stack([np.clip(p_x - gains.roll.k_d * rates[:, 0], -limits[0], limits[0]),
                     np.clip(p_y - gains.pitch.k_d * rates[:, 1], -limits[1], limits[1]),
                     np.clip(-p_z + gains.yaw.k_d * rates[:, 2], -limits[2], limits[2])], -1)


def capture_study(n_runs: int = 200, pointing: str = "BODY", gains: CpdGains | None = None,
                  duration_s: float = 40.0, period_s: float = 0.01, substeps: int = 5,
                  sigma_angle: float = math.radians(10.0), sigma_rate: float = math.radians(10.0),
                  seed: int = 20261122, vehicle: VehicleModel | None = None,
                  tau: float = 0.1, m_xc_max: float = 30.0,
                  delta_c_max: float = math.radians(0.65), controller: str = "kernel",
                  shaping_eta: float = 0.5) -> CaptureResult:
    """Attitude capture from Table 4 dispersions with CPD in the loop.

    Truth: body-from-c DCM propagated with RK4 (Cdot = -[w x] C), eqs. (13)-(15) with l(t), I(t) of
    eq. (53), actuators of eqs. (16)-(18) with their hardware limits (Table 2: 60 N m, 3 deg).
    Command: alpha_c = beta_c = 0 at xi = phi = 0 (the thrust direction at ignition), roll 0.
    controller: "kernel" (the flight CPD through cffi, with `pointing`; it gets the Euler angles of
    the truth DCM and the true body rates every period_s), "numpy" (prototype_body_cpd, plain law:
    a cross-check of the kernel in BODY mode) or "shaped" (prototype_body_cpd with shaping_eta)."""
    vehicle = vehicle or leo_geo_vehicle()
    gains = gains or design_gains(vehicle)
    if controller not in ("kernel", "numpy", "shaped"):
        raise ValueError(f"unknown controller {controller!r}")
    rng = np.random.default_rng(seed)
    n = n_runs
    euler0 = rng.normal(0.0, sigma_angle, (3, n))          # psi, theta, phi about the command
    rates = rng.normal(0.0, sigma_rate, (n, 3))            # P, Q, R
    c_ba = _euler_dcm(euler0[0], euler0[1], euler0[2])
    c_bc = c_ba @ R_A                                      # body-from-c
    act = np.zeros((n, 3))                                 # M_x~, D_y~, D_z~
    t_c = R_A.T @ np.array([1.0, 0.0, 0.0])                # commanded direction = a1 = c2 = t
    hw = np.array([60.0, math.radians(3.0), math.radians(3.0)])
    taus = np.array([tau, tau, tau])
    limits = np.array([m_xc_max, delta_c_max, delta_c_max])
    g0 = vehicle.effectiveness(0.0)
    a_sat = (float(g0[0]) * m_xc_max, float(g0[1]) * delta_c_max)
    ctls: list[Any] = []
    if controller == "kernel":
        from ogk_bindings import cpd  # the bindings are needed only here
        ctls = [cpd.Cpd(cpd.CpdConfig(**gains.as_config_dict(), m_xc_max=m_xc_max,
                                      delta_yc_max=delta_c_max, delta_zc_max=delta_c_max,
                                      tau_x=tau, tau_y=tau, tau_z=tau,
                                      pointing=cpd.Pointing[pointing]))
                for _ in range(n)]
    n_samples = int(round(duration_s / period_s))
    errors = np.empty((n_samples, n))
    h = period_s / substeps

    def deriv(t: float, c: F64, w: F64, a: F64, cmd: F64) -> tuple[F64, F64, F64]:
        ix, iy, iz = vehicle.inertia_kg_m2(t)
        tl = vehicle.thrust_n * vehicle.arm_m(t)
        mx, dy, dz = (np.clip(a[:, k], -hw[k], hw[k]) for k in range(3))
        p, q, r = w[:, 0], w[:, 1], w[:, 2]
        wdot = np.stack([(iy - iz) / ix * q * r + mx / ix,
                         (iz - ix) / iy * p * r + tl * np.cos(dz) * np.sin(dy) / iy,
                         (ix - iy) / iz * p * q - tl * np.sin(dz) / iz], -1)
        skew = np.zeros((len(w), 3, 3))
        skew[:, 0, 1], skew[:, 0, 2], skew[:, 1, 2] = -r, q, -p
        skew[:, 1, 0], skew[:, 2, 0], skew[:, 2, 1] = r, -q, p
        return -skew @ c, wdot, (cmd - a) / taus

    cmd = np.zeros((n, 3))
    for k in range(n_samples):
        t = k * period_s
        errors[k] = np.degrees(np.arccos(np.clip(c_bc[:, 0, :] @ t_c, -1.0, 1.0)))
        if controller == "kernel":
            psi, theta, phi = _dcm_euler(c_bc @ R_A.T)
            for i, ctl in enumerate(ctls):
                _, out = ctl.step_or_safe(cpd.CpdInput(
                    psi=float(psi[i]), theta=float(theta[i]), phi_roll=float(phi[i]),
                    rate_p=float(rates[i, 0]), rate_q=float(rates[i, 1]),
                    rate_r=float(rates[i, 2])))
                cmd[i] = (out.m_xc, out.delta_yc, out.delta_zc)
        else:
            cmd = prototype_body_cpd(c_bc, rates, t_c, gains, limits,
                                     shaping_eta if controller == "shaped" else None, a_sat)
        for s in range(substeps):  # RK4 on (C, w, actuators), command held
            ts = t + s * h
            k1 = deriv(ts, c_bc, rates, act, cmd)
            x2 = [v + 0.5 * h * d for v, d in zip((c_bc, rates, act), k1)]
            k2 = deriv(ts + 0.5 * h, *x2, cmd)
            x3 = [v + 0.5 * h * d for v, d in zip((c_bc, rates, act), k2)]
            k3 = deriv(ts + 0.5 * h, *x3, cmd)
            x4 = [v + h * d for v, d in zip((c_bc, rates, act), k3)]
            k4 = deriv(ts + h, *x4, cmd)
            c_bc, rates, act = (v + h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4) for v, a1, a2, a3, a4
                                in zip((c_bc, rates, act), k1, k2, k3, k4))
        u, _, vt = np.linalg.svd(c_bc)                     # re-orthonormalise the DCM
        c_bc = u @ vt
    above = errors >= 1.0
    last_above = np.where(above.any(axis=0), n_samples - 1 - np.argmax(above[::-1], axis=0), -1)
    capture = np.where(last_above == n_samples - 1, np.inf, (last_above + 1) * period_s)
    label = pointing if controller == "kernel" else f"{controller} BODY"
    return CaptureResult(pointing=label, final_error_deg=errors[-1],
                         max_error_deg=errors.max(axis=0), capture_time_s=capture,
                         duration_s=duration_s)


def capture_report(n_runs: int, duration_s: float = 100.0) -> str:
    """Capture statistics of both pointing modes (re-derived gains, 100 Hz)."""
    lines = [f"capture study: {n_runs} draws, Table 4 sigmas (10 deg, 10 deg/s), "
             f"{duration_s:.0f} s, 100 Hz CPD, re-derived gains; capture = pointing error "
             f"below 1 deg for good"]
    runs = (("EULER", "kernel"), ("BODY", "kernel"), ("BODY", "numpy"), ("BODY", "shaped"))
    for mode, controller in runs:
        res = capture_study(n_runs, mode, duration_s=duration_s, controller=controller)
        cap = res.capture_time_s
        finite = cap[np.isfinite(cap)]
        p50, p90, p99 = np.percentile(finite, [50, 90, 99])
        late = ", ".join(f"{int((cap > t).sum())} after {t:.0f} s" for t in (20, 40, 60, 80))
        lines.append(
            f"  {res.pointing:12s}: never {int(res.lost.sum())}/{n_runs}; "
            f"capture time median {p50:.1f} s, "
            f"90% {p90:.1f} s, 99% {p99:.1f} s, max {finite.max():.1f} s ({late}); "
            f"max error median {np.median(res.max_error_deg):.1f} deg, "
            f"90% {np.percentile(res.max_error_deg, 90):.1f} deg, worst "
            f"{res.max_error_deg.max():.1f} deg")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m ogk_host.cpd_design", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--capture", type=int, default=0, metavar="N",
                        help="also run the attitude capture study with N draws per mode")
    args = parser.parse_args(argv)
    print(report())
    if args.capture:
        print(capture_report(args.capture))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
