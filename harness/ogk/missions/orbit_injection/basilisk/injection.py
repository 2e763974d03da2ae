"""An orbit-injection burn flown in Basilisk, ogk's flight software in the loop: the independent
truth model of docs/guides/basilisk.md.

Basilisk's Spacecraft hub (RK4 on Cartesian position, velocity, MRP attitude and body rates, its
own equations of motion), Basilisk's point-mass gravity (gravityEffector, the scenario's mu; no
J2: ogk's truth model has none), the engine's force and torque through extForceTorque (body
frame), mass depletion as the hub's mass and inertia set every step by TvcEnginePlant, navigation
by simpleNav (no errors: ogk's campaigns fly perfect navigation). One run per simulation, with the
run's draws of ogk's campaign (initial state and attitude, eq. 55 thrust, Table 5 actuation noise).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray
from ogk_bindings.extras import need

from ogk.missions.orbit_injection import truth as tm
from ogk.missions.orbit_injection.dispersions import ActuationNoise, DispersionSwitches, RunDraws
from ogk.missions.orbit_injection.nominal_ref import circular_speed
from ogk.missions.orbit_injection.sil import ERROR_KEYS, SilSettings, initial_state

from . import frames
from .modules import OgkInjectionFsw, TvcEnginePlant

# Basilisk is the extra ogk[basilisk] (ogk_bindings.extras): one line naming it when it is missing
_BASILISK = "the Basilisk truth model of ogk.missions.orbit_injection.basilisk"
extForceTorque = need("Basilisk.simulation.extForceTorque", "basilisk", _BASILISK)
simpleNav = need("Basilisk.simulation.simpleNav", "basilisk", _BASILISK)
spacecraft = need("Basilisk.simulation.spacecraft", "basilisk", _BASILISK)
SimulationBaseClass = need("Basilisk.utilities.SimulationBaseClass", "basilisk", _BASILISK)
macros = need("Basilisk.utilities.macros", "basilisk", _BASILISK)
simIncludeGravBody = need("Basilisk.utilities.simIncludeGravBody", "basilisk", _BASILISK)

F64 = NDArray[np.float64]
HISTORY_KEYS = ("r_m", "xi_rad", "phi_rad", "vr_mps", "vt_mps", "vn_mps", "psi_rad",
                "theta_rad", "phi_roll_rad", "alpha_c_rad", "beta_c_rad")


@dataclasses.dataclass
class BasiliskFlight:
    """One run flown in Basilisk."""

    final_nav: F64                 #: [r, xi, phi, v_r, v_t, v_n] at cut-off
    errors: dict[str, float]       #: sil.ERROR_KEYS -> value (NaN if failed)
    failure: str                   #: "" or a sil.FAILURE_REASONS entry
    t_s: F64                       #: history sample times [s]
    history: dict[str, F64]        #: HISTORY_KEYS -> (n_samples,)
    steps: int                     #: dynamics steps flown


def _gravity(sc: Any, mu: float) -> Any:
    """Basilisk's Earth as the central point mass, with the scenario's mu."""
    factory = simIncludeGravBody.gravBodyFactory()
    earth = factory.createEarth()
    earth.isCentralBody = True
    earth.mu = mu
    factory.addBodiesTo(sc)
    return factory


def fly(scn: Any, ref: Any, tables: Any, draws: RunDraws, generator: np.random.Generator,
        switches: DispersionSwitches, settings: SilSettings = SilSettings(),
        history_s: float = 0.0) -> BasiliskFlight:
    """Flies run draws.run_id[0] (draws of one run; `generator` positioned for its actuation
    noise, as draw_runs returns it) in Basilisk with the dynamics step settings.truth_step_s."""
    if draws.n_runs != 1:
        raise ValueError("one run per Basilisk simulation")
    h = settings.truth_step_s
    h_ns = macros.sec2nano(h)
    x0 = initial_state(scn, ref, draws, "6dof")[:, 0]

    sim = SimulationBaseClass.SimBaseClass()
    proc = sim.CreateNewProcess("injection")
    proc.addTask(sim.CreateNewTask("loop", h_ns))
    sc = spacecraft.Spacecraft()
    sc.ModelTag = "vehicle"
    r_n, v_n = frames.cartesian_from_ogk(x0[:6])
    sc.hub.r_CN_NInit = [[float(v)] for v in r_n]
    sc.hub.v_CN_NInit = [[float(v)] for v in v_n]
    sc.hub.sigma_BNInit = [[v] for v in frames.sigma_bn_of(tm.dcm_from_quat(x0[6:10]))]
    sc.hub.omega_BN_BInit = [[float(v)] for v in x0[10:13]]
    grav = _gravity(sc, scn.mu_m3_s2)
    nav = simpleNav.SimpleNav()
    nav.scStateInMsg.subscribeTo(sc.scStateOutMsg)
    fsw = OgkInjectionFsw(scn, ref, tables, settings)
    fsw.navTransInMsg.subscribeTo(nav.transOutMsg)
    fsw.navAttInMsg.subscribeTo(nav.attOutMsg)
    noise = ActuationNoise(scn, [generator], switches.actuation)
    plant = TvcEnginePlant(scn, ref.tf_s, sc.hub, h, settings.control_rate_hz,
                           draws.thrust_coeffs[0] if switches.thrust else None, noise)
    plant.tvcCmdInMsg.subscribeTo(fsw.tvcCmdOutMsg)
    plant.cmdTorqueInMsg.subscribeTo(fsw.cmdTorqueOutMsg)
    plant.thrOnTimeInMsg.subscribeTo(fsw.thrOnTimeOutMsg)
    ext = extForceTorque.ExtForceTorque()
    ext.ModelTag = "engine"
    ext.cmdForceBodyInMsg.subscribeTo(plant.cmdForceOutMsg)
    ext.cmdTorqueInMsg.subscribeTo(plant.cmdTorqueOutMsg)
    sc.addDynamicEffector(ext)
    # one loop per step, in this order: dynamics to t, navigation, flight software, plant,
    # effector (reads the force it holds over [t, t + h])
    for model, priority in ((sc, 100), (nav, 90), (fsw, 80), (plant, 70), (ext, 60)):
        sim.AddModelToTask("loop", model, priority)
    sim.InitializeSimulation()

    t_max = settings.t_max_s if settings.t_max_s is not None else 1.5 * ref.tf_s + 20.0
    ticks = max(1, int(round(1.0 / (settings.control_rate_hz * h))))
    # Basilisk runs whole chunks of steps (one ExecuteSimulation each) while the cut-off is far,
    # then step by step: the cut-off predicted at a tick is never later than margin_s after it
    # moves (guidance samples every Delta t_S; checked below, an overshoot raises)
    chunk = ticks * int(round(settings.control_rate_hz * history_s)) if history_s else \
        ticks * int(round(settings.control_rate_hz))
    margin_s = 10.0 * scn.sample_interval_s
    hist_t: list[float] = []
    rows: list[list[float]] = []
    k, failure, t_end = 0, "", math.nan
    sim.ConfigureStopTime(0)
    sim.ExecuteSimulation()
    while True:
        t = k * h
        state = sc.scStateOutMsg.read()
        if t > fsw.t_cutoff_s + 1e-9:
            raise RuntimeError(f"a chunk of Basilisk steps passed the cut-off at "
                               f"{fsw.t_cutoff_s:.6f} s: margin_s {margin_s} s is too small")
        if history_s and k % chunk == 0 and fsw.last_tick is not None:
            x = frames.ogk_from_cartesian(state.r_BN_N, state.v_BN_N)
            att = frames.ogk_attitude(state.sigma_BN, state.omega_BN_B)
            tick = fsw.last_tick
            hist_t.append(t)
            rows.append([*x, *att[:3], float(tick.alpha_rad[0]), float(tick.beta_rad[0])])
        if fsw.failure:
            failure = fsw.failure
            break
        remaining = fsw.t_cutoff_s - t
        if remaining <= 0.0:                 # cut off at this tick (ogk's "late" runs)
            t_end = t
            break
        if remaining <= h:
            # land exactly on the cut-off: the plant wrote the averages over [t, t_c] (its
            # on-time), the hub is integrated over that partial step only (1 ns resolution)
            t_end = fsw.t_cutoff_s
            sc.UpdateState(int(round(t_end * 1e9)))
            state = sc.scStateOutMsg.read()
            break
        if t > t_max:
            failure = "no_termination"
            break
        steps = 1
        if remaining > margin_s + chunk * h:
            steps = chunk - k % chunk
        k += steps
        sim.ConfigureStopTime(k * h_ns)
        sim.ExecuteSimulation()
    if np.isfinite(np.asarray(state.r_BN_N)).all() and not failure:
        final = frames.ogk_from_cartesian(state.r_BN_N, state.v_BN_N)
    else:
        final = np.full(6, np.nan)
        failure = failure or "nan"
    vc = circular_speed(scn)
    errors = dict(zip(ERROR_KEYS, (final[0] - scn.target_radius_m, math.degrees(final[2]),
                                   final[3], final[4] - vc, final[5], t_end)))
    if failure:
        errors = {key: math.nan for key in ERROR_KEYS}
    del grav
    hist = np.array(rows) if rows else np.zeros((0, len(HISTORY_KEYS)))
    return BasiliskFlight(final, errors, failure, np.array(hist_t),
                          {key: hist[:, i] for i, key in enumerate(HISTORY_KEYS)}, k)
