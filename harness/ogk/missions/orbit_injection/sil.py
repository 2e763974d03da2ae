"""Closed loop of the LEO-to-GEO burn: truth model + guidance + attitude control, N runs at once.

Timing (docs/guides/sil.md):
  * guidance samples at t_k = k Delta t_S (2 s, scenario), with perfect navigation;
  * attitude control at `control_rate_hz` (50 Hz), zero-order hold; actuation noise drawn per
    control step and held;
  * truth: fixed-step RK4 with `truth_substeps` steps per control step (h = 20 ms by default), each
    run's last step shortened to land exactly on its engine cut-off time.
Truth "6dof" (truth.rhs_6dof, CPD in the loop) or "point-mass" (truth.rhs_point_mass, thrust along the
guidance command evaluated at every RK4 stage, no attitude control).

Injection errors at cut-off are taken w.r.t. the eq. (20) targets: r - R_f, phi, v_r,
v_t - sqrt(mu / R_f), v_n, and the cut-off time t_f.
"""
from __future__ import annotations

import dataclasses
from typing import Callable, Protocol

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection import derive
from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from . import truth as tm
from .attitude import AttitudeCommand, AttitudeControl, CpdBatchControl
from .cutoff import EnergyCutoff
from .terminal import TerminalSteering
from .dispersions import ActuationNoise, DispersionSwitches, RunDraws
from .guidance import Guidance
from .nominal_ref import NominalReference, circular_speed

F64 = NDArray[np.float64]

ERROR_KEYS = ("dr_f_m", "dphi_f_deg", "dvr_f_mps", "dvt_f_mps", "dvn_f_mps", "tf_s")
RATE_KEYS = ("Mx_dot_Nmps", "Dy_dot_degps", "Dz_dot_degps")
TRUTHS = ("6dof", "point-mass")
FAILURE_REASONS = ("nan", "guidance", "attitude_control", "no_termination", "cutoff", "terminal")
END_GAMES = ("scenario", "paper")
HISTORY_KEYS = ("r_m", "xi_rad", "phi_rad", "vr_mps", "vt_mps", "vn_mps", "alpha_c_rad",
                "beta_c_rad", "Mx_Nm", "Dy_rad", "Dz_rad", "psi_rad", "theta_rad", "phi_roll_rad",
                "psi_c_rad", "theta_c_rad", "phi_c_rad", "alpha_a_rad", "beta_a_rad")


@dataclasses.dataclass(frozen=True)
class SilSettings:
    """Loop rates and options."""

    truth: str = "6dof"
    control_rate_hz: float = 50.0     #: attitude-control rate (zero-order hold)
    truth_substeps: int = 1           #: RK4 steps per control step (h = 1 / (rate * substeps))
    t_max_s: float | None = None      #: no cut-off by then -> "no_termination" (default 1.5 t_f* + 20 s)
    history_runs: int = 0             #: record histories of the runs with run_id < history_runs
    history_every: int = 5            #: control steps between history samples (0.1 s)
    cpd_gains: str | None = None      #: "printed" / "rederived" (default: scenario's flown set)
    cpd_pointing: str = "body"        #: "body" (flown) or "euler" (eqs. 45-46 literally)
    #: "scenario": the scenario's [guidance.end_game] cut-off and end sampling; "paper": cut-off
    #: predicted at the samples (eq. 32) and Delta t_S throughout, whatever the scenario says
    end_game: str = "scenario"

    @property
    def truth_step_s(self) -> float:
        return 1.0 / (self.control_rate_hz * self.truth_substeps)


@dataclasses.dataclass(frozen=True)
class EndGamePlan:
    """How a run ends (docs/design/vtd-nog.md, "End-game"): the cut-off decision and the sampling."""

    energy_cutoff: bool               #: kernel ogk_cutoff decides the cut-off between samples
    fine_interval_s: float | None     #: sampling interval near the end (None: Delta t_S throughout)
    fine_window_s: float              #: ... while the predicted time to go is at most this
    terminal_window_s: float = 0.0    #: kernel ogk_terminal steers the last seconds along v_go (0: never)

    @classmethod
    def of(cls, scn: OrbitInjectionScenario, settings: "SilSettings") -> "EndGamePlan":
        if settings.end_game not in END_GAMES:
            raise ValueError(f"end_game must be one of {END_GAMES}, got {settings.end_game!r}")
        if settings.end_game == "paper":
            return cls.none()
        derive.require_resolved(scn)
        eg = scn.end_game
        assert eg.fine_window_s is not None and eg.terminal_window_s is not None
        fine = None
        if eg.fine_sample_interval_s is not None and eg.fine_window_s > 0.0:
            # a whole number of control periods (at least one): samples fall on control steps
            ctrl_dt = 1.0 / settings.control_rate_hz
            fine = max(1, round(eg.fine_sample_interval_s / ctrl_dt)) * ctrl_dt
        return cls(eg.cutoff == "energy", fine, eg.fine_window_s, eg.terminal_window_s)

    @classmethod
    def none(cls) -> "EndGamePlan":
        """Nothing beyond the paper: cut-off predicted at the samples, Delta t_S throughout."""
        return cls(False, None, 0.0, 0.0)

    @classmethod
    def flown_by(cls, scn: OrbitInjectionScenario, settings: "SilSettings", guidance: object
                 ) -> "EndGamePlan":
        """The plan a guidance flies: an open-loop reference (flies_end_game = False) flies none."""
        if not getattr(guidance, "flies_end_game", True):
            return cls.none()
        return cls.of(scn, settings)


@dataclasses.dataclass
class History:
    """Sampled time histories of some runs: data[key] (n_samples, K); NaN after cut-off."""

    run_id: NDArray[np.int64]
    t_s: F64
    data: dict[str, F64]


@dataclasses.dataclass
class SilResult:
    """Outcome of `fly_runs` for N runs (run-major arrays)."""

    run_id: NDArray[np.int64]
    final_state: F64                   #: (N, 6) [r, xi, phi, v_r, v_t, v_n] at cut-off (SI)
    errors: dict[str, F64]             #: ERROR_KEYS -> (N,), NaN for failed runs
    max_rates: dict[str, F64]          #: RATE_KEYS -> (N,), NaN for point-mass
    failure: list[str]                 #: "" or a FAILURE_REASONS entry, per run
    history: History | None
    truth_steps: int
    control_steps: int


def initial_state(scn: OrbitInjectionScenario, ref: NominalReference, draws: RunDraws,
                  truth: str) -> F64:
    """Component-major initial truth state (n_state, N): nominal ignition state + Table 3 errors;
    for 6-DOF the nominal attitude points x_b along u*(0) with the commanded roll, plus Table 4
    errors on the Euler angles and the rates; actuators at rest."""
    n = draws.n_runs
    x_trans = ref.initial_state[None, :] + draws.d_state
    if truth == "point-mass":
        return np.ascontiguousarray(x_trans.T)
    x = np.zeros((tm.N_6DOF, n))
    x[:6] = x_trans.T
    u0 = ref.control(np.array(0.0))
    psi0, theta0 = tm.commanded_attitude(u0[0], u0[1], ref.initial_state[1],
                                         ref.initial_state[2])
    euler = np.array([psi0, theta0, scn.cpd.roll_command_rad])[None, :] + draws.d_attitude
    x[tm.Q0:tm.Q3 + 1] = tm.quat_from_euler(euler[:, 0], euler[:, 1], euler[:, 2])
    x[tm.RATE_P:tm.RATE_R + 1] = draws.rates0.T
    return x


@dataclasses.dataclass(frozen=True)
class Tick:
    """What a flight computer answers at one control tick, per run (N,); inactive runs: NaN."""

    failure: list[str]                 #: "" or a FAILURE_REASONS entry
    t_predicted_s: F64                 #: guidance's predicted cut-off [s]
    t_cutoff_s: F64                    #: cut-off in force [s]
    alpha_rad: F64                     #: thrust-direction command flown [rad]
    beta_rad: F64
    attitude: AttitudeCommand          #: CPD's output


class FlightComputer(Protocol):
    """The flight software of N runs as one call per control tick k: times t_s (N,), navigation
    nav (N, 6) [r, xi, phi, v_r, v_t, v_n], attitude (N, 6) [psi, theta, phi rad, p, q, r rad/s],
    and which runs still fly (ogk.missions.orbit_injection.pil: the flight program on the target)."""

    def tick(self, k: int, t_s: F64, nav: F64, attitude: F64,
             active: NDArray[np.bool_]) -> Tick: ...


RhsFn = Callable[[F64 | float, F64, F64], None]   #: rhs(t, x, out): writes dx/dt into out


class _Rk4:
    """RK4 with preallocated stage buffers."""

    def __init__(self, shape: tuple[int, int]) -> None:
        self.k = [np.empty(shape) for _ in range(4)]

    def step(self, rhs: RhsFn, t: F64 | float, x: F64, h: F64, h_time: F64 | float) -> F64:
        """x(t + h) for per-run steps h (N,); stage times use h_time (a scalar when every run
        that moves takes the same step, so time-only quantities stay scalars)."""
        k1, k2, k3, k4 = self.k
        half = 0.5 * h
        t_half = t + 0.5 * h_time
        rhs(t, x, k1)
        rhs(t_half, x + half * k1, k2)
        rhs(t_half, x + half * k2, k3)
        rhs(t + h_time, x + h * k3, k4)
        k2 += k3
        k2 *= 2.0
        k1 += k2
        k1 += k4
        k1 *= h / 6.0
        return x + k1


def fly_runs(scn: OrbitInjectionScenario, ref: NominalReference, draws: RunDraws,
             generators: list[np.random.Generator], switches: DispersionSwitches,
             guidance: Guidance, settings: SilSettings = SilSettings(),
             attitude_control: AttitudeControl | None = None,
             flight_computer: FlightComputer | None = None) -> SilResult:
    """Flies N runs from ignition to engine cut-off (or failure). `scn` is resolved where it was
    loaded (nominal_ref.resolved_with_reference): the end-game stages refuse a setting left to
    t_f*. With `flight_computer` (6-DOF truth) the whole control tick is the flight program's
    (processor in the loop): guidance, the end-game and CPD are not called here."""
    if settings.truth not in TRUTHS:
        raise ValueError(f"truth must be one of {TRUTHS}, got {settings.truth!r}")
    six_dof = settings.truth == "6dof"
    n = draws.n_runs
    if flight_computer is not None and not six_dof:
        raise ValueError("a flight computer flies on the 6-DOF truth")
    params = tm.TruthParams.from_scenario(scn, ref.tf_s)
    ctrl_dt = 1.0 / settings.control_rate_hz
    h = settings.truth_step_s
    sample_every = scn.sample_interval_s / ctrl_dt
    if abs(sample_every - round(sample_every)) > 1e-9 or round(sample_every) < 1:
        raise ValueError("the guidance sampling interval must be a multiple of the control period")
    sample_every = int(round(sample_every))
    plan = EndGamePlan.flown_by(scn, settings, guidance)
    fine_every = sample_every
    if plan.fine_interval_s is not None:
        fine_every = int(round(plan.fine_interval_s / ctrl_dt))   # whole periods (EndGamePlan.of)
    energy_cut = EnergyCutoff(scn, n, ctrl_dt) if plan.energy_cutoff else None
    terminal = TerminalSteering(scn, n) if plan.terminal_window_s > 0.0 else None
    t_max = settings.t_max_s if settings.t_max_s is not None else 1.5 * ref.tf_s + 20.0
    vc = circular_speed(scn)

    x = initial_state(scn, ref, draws, settings.truth)
    coeffs = np.ascontiguousarray(draws.thrust_coeffs.T) if switches.thrust else None
    noise_src = ActuationNoise(scn, generators, switches.actuation and six_dof)
    if six_dof and attitude_control is None:
        attitude_control = CpdBatchControl(scn, n, settings.cpd_gains, settings.cpd_pointing,
                                           ctrl_dt)
    command = np.zeros((3, n))                   # held [M_xc, Delta_yc, Delta_zc]
    noise: F64 | None = None
    alpha_c, beta_c = np.zeros(n), np.zeros(n)
    att_cmd = None

    done = np.zeros(n, dtype=bool)
    failure = [""] * n
    tf = np.full(n, np.nan)
    final = np.full((n, 6), np.nan)
    max_rates = np.zeros((3, n)) if six_dof else np.full((3, n), np.nan)
    tau = np.array(params.time_constant)[:, None]
    out_max = np.array(params.output_max)[:, None]

    hist_cols = np.flatnonzero(draws.run_id < settings.history_runs)
    hist_t: list[float] = []
    hist_rows: dict[str, list[F64]] = {k: [] for k in HISTORY_KEYS}

    def fail(mask: NDArray[np.bool_], reason: str) -> None:
        for i in np.flatnonzero(mask & ~done):
            failure[i] = reason
        done[mask] = True

    def finish(mask: NDArray[np.bool_], t_cut: F64) -> None:
        tf[mask] = t_cut[mask]
        final[mask] = x[:6, mask].T
        done[mask] = True

    factor = tm.ThrustFactorCache(params, coeffs)
    if six_dof:
        def rhs(t: F64 | float, xs: F64, out: F64) -> None:
            tm.rhs_6dof(params, t, xs, command, noise, factor(t), out)
    else:
        # the law's command in continuous time, except where the terminal stage is engaged: its
        # command, computed at the control step, is held over it (zero-order hold, as the 6-DOF
        # loop holds the attitude command)
        held = np.zeros(n, dtype=bool)
        held_alpha = np.zeros(n)
        held_beta = np.zeros(n)

        def rhs(t: F64 | float, xs: F64, out: F64) -> None:
            a_c, b_c = guidance.command(np.broadcast_to(t, (n,)))
            if held.any():
                a_c = np.where(held, held_alpha, a_c)
                b_c = np.where(held, held_beta, b_c)
            tm.rhs_point_mass(params, t, xs, a_c, b_c, factor(t), out)
    rk4 = _Rk4(x.shape)
    cutoff = np.full(n, np.inf)
    predicted = np.full(n, np.inf)
    j = 0
    control_steps = 0
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        while not done.all():
            t = j * h
            t_run = np.where(done, tf, t)
            active = ~done
            if t > t_max:
                fail(active, "no_termination")
                break
            if j % settings.truth_substeps == 0 and flight_computer is not None:
                # the flight software on the target: one exchange per run and tick (ogk.sil.pil)
                k = j // settings.truth_substeps
                control_steps += 1
                psi, theta, roll = tm.euler_from_quat(x[tm.Q0:tm.Q3 + 1])
                att = np.stack([psi, theta, roll, x[tm.RATE_P], x[tm.RATE_Q], x[tm.RATE_R]],
                               axis=1)
                tick = flight_computer.tick(k, t_run, np.ascontiguousarray(x[:6].T), att, active)
                for reason in sorted(set(tick.failure) - {""}):
                    fail(active & np.array([f == reason for f in tick.failure]), reason)
                active = ~done
                predicted, cutoff = tick.t_predicted_s, tick.t_cutoff_s
                alpha_c, beta_c = tick.alpha_rad, tick.beta_rad
                att_cmd = tick.attitude
                command = np.where(active, np.stack([att_cmd.m_xc, att_cmd.delta_yc,
                                                     att_cmd.delta_zc]), command)
                noise = noise_src.next() if switches.actuation else None
                max_rates = _actuator_rates(x, command, noise, tau, out_max, active, max_rates)
                if hist_cols.size and k % settings.history_every == 0:
                    _record(hist_t, hist_rows, hist_cols, t, x, done, alpha_c, beta_c, att_cmd,
                            noise, params, six_dof)
            elif j % settings.truth_substeps == 0:          # control sample
                k = j // settings.truth_substeps
                control_steps += 1
                due = np.full(n, k % sample_every == 0)
                if plan.fine_interval_s is not None and k % fine_every == 0:
                    # per run: the schedule of one run never depends on the others in its chunk
                    due |= (predicted - t_run) <= plan.fine_window_s
                if due.any():
                    guidance.sample(t_run, np.ascontiguousarray(x[:6].T), due)
                    failed_fn = getattr(guidance, "failed", None)
                    if failed_fn is not None:
                        fail(np.asarray(failed_fn(), dtype=bool) & active, "guidance")
                predicted = np.asarray(guidance.cutoff_time(), dtype=np.float64)
                fail(np.isnan(predicted) & ~done, "guidance")
                active = ~done
                cutoff = predicted
                if energy_cut is not None:
                    known = active & np.isfinite(predicted)
                    cutoff = np.where(known, energy_cut.step(known, t_run, x[:6].T, predicted),
                                      predicted)
                    fail(energy_cut.failed() & known, "cutoff")
                    active = ~done
                alpha_c, beta_c = (np.asarray(v, dtype=np.float64)
                                   for v in guidance.command(t_run))
                fail(~(np.isfinite(alpha_c) & np.isfinite(beta_c)) & active, "guidance")
                active = ~done
                if terminal is not None:
                    known = active & np.isfinite(predicted)
                    alpha_c, beta_c = terminal.step(known, t_run, x[:6].T, predicted, alpha_c,
                                                    beta_c)
                    fail(terminal.failed() & known, "terminal")
                    active = ~done
                    if not six_dof:
                        held[:] = terminal.engaged != 0
                        held_alpha[:] = alpha_c
                        held_beta[:] = beta_c
                if six_dof:
                    psi, theta, roll = tm.euler_from_quat(x[tm.Q0:tm.Q3 + 1])
                    att = np.stack([psi, theta, roll, x[tm.RATE_P], x[tm.RATE_Q], x[tm.RATE_R]],
                                   axis=1)
                    att_cmd = attitude_control.step(t_run, att, alpha_c, beta_c, x[tm.XI],
                                                    x[tm.PHI], active)
                    fail((att_cmd.status != 0) & active, "attitude_control")
                    active = ~done
                    command = np.where(active, np.stack([att_cmd.m_xc, att_cmd.delta_yc,
                                                         att_cmd.delta_zc]), command)
                    noise = noise_src.next() if switches.actuation else None
                    max_rates = _actuator_rates(x, command, noise, tau, out_max, active,
                                                max_rates)
                if hist_cols.size and k % settings.history_every == 0:
                    _record(hist_t, hist_rows, hist_cols, t, x, done, alpha_c, beta_c, att_cmd,
                            noise, params, six_dof)
            # truth step, each run landing exactly on its cut-off time
            remaining = cutoff - t
            late = active & (remaining <= 0.0)
            if late.any():
                finish(late, t_run)
                active = ~done
            if not active.any():
                break
            step = np.where(active, np.minimum(remaining, h), 0.0)
            landing = active & (remaining <= h)
            # all runs share the time t except on a landing step (the time-only quantities are
            # then scalars); the time of a finished run does not matter (its step is 0)
            if landing.any():
                x = rk4.step(rhs, t_run, x, step, step)
            else:
                x = rk4.step(rhs, t, x, step, h)
            if six_dof:
                tm.normalise_quaternion(x)
            fail(~np.isfinite(x).all(axis=0) & active, "nan")
            finish(landing & ~done, cutoff)
            j += 1

    ok = np.array([f == "" for f in failure]) & np.isfinite(tf)
    errors = {
        "dr_f_m": final[:, 0] - scn.target_radius_m,
        "dphi_f_deg": np.degrees(final[:, 2]),
        "dvr_f_mps": final[:, 3],
        "dvt_f_mps": final[:, 4] - vc,
        "dvn_f_mps": final[:, 5],
        "tf_s": tf.copy(),
    }
    for v in errors.values():
        v[~ok] = np.nan
    rates = {"Mx_dot_Nmps": max_rates[0], "Dy_dot_degps": np.degrees(max_rates[1]),
             "Dz_dot_degps": np.degrees(max_rates[2])}
    history = None
    if hist_cols.size:
        history = History(run_id=draws.run_id[hist_cols], t_s=np.array(hist_t),
                          data={k: np.array(v) for k, v in hist_rows.items()})
    return SilResult(run_id=draws.run_id.copy(), final_state=final, errors=errors,
                     max_rates=rates, failure=failure, history=history, truth_steps=j,
                     control_steps=control_steps)


def _actuator_rates(x: F64, command: F64, noise: F64 | None, tau: F64, out_max: F64,
                    active: NDArray[np.bool_], max_rates: F64) -> F64:
    """Eq. (47) check: d/dt of the actuator outputs is (cmd - state)/tau while unsaturated; it is
    largest right after a command change (exponential lag). The running maximum per run."""
    state = x[tm.ACT_MX:tm.ACT_DZ + 1]
    inside = np.abs(state + (noise if noise is not None else 0.0)) < out_max
    rate = np.abs(command - state) / tau * inside
    return np.where(active, np.maximum(max_rates, rate), max_rates)


def _record(hist_t: list[float], rows: dict[str, list[F64]], cols: NDArray[np.int64], t: float,
            x: F64, done: NDArray[np.bool_], alpha_c: F64, beta_c: F64, att_cmd, noise,
            params: tm.TruthParams, six_dof: bool) -> None:
    """Appends one history sample of the runs `cols` (NaN once cut off)."""
    hist_t.append(t)
    xs = x[:, cols]
    nan = np.full(cols.size, np.nan)
    vals: dict[str, F64] = {k: xs[i] for i, k in enumerate(HISTORY_KEYS[:6])}
    vals["alpha_c_rad"], vals["beta_c_rad"] = alpha_c[cols], beta_c[cols]
    if six_dof:
        mx, dy, dz = tm.actuator_outputs(params, xs, None if noise is None else noise[:, cols])
        psi, theta, roll = tm.euler_from_quat(xs[tm.Q0:tm.Q3 + 1])
        a_a, b_a = tm.thrust_angles(psi, theta, roll, xs[tm.XI], xs[tm.PHI], dy, dz)
        vals.update(Mx_Nm=mx, Dy_rad=dy, Dz_rad=dz, psi_rad=psi, theta_rad=theta,
                    phi_roll_rad=roll, psi_c_rad=att_cmd.psi_c[cols],
                    theta_c_rad=att_cmd.theta_c[cols], phi_c_rad=att_cmd.phi_c[cols],
                    alpha_a_rad=a_a, beta_a_rad=b_a)
    else:
        vals.update({k: nan for k in HISTORY_KEYS[8:17]})
        vals.update(alpha_a_rad=alpha_c[cols], beta_a_rad=beta_c[cols])
    gone = done[cols]
    for key in HISTORY_KEYS:
        v = np.array(vals[key], dtype=np.float64)
        v[gone] = np.nan
        rows[key].append(v)

