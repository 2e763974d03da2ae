"""Basilisk modules: ogk's flight software (OgkInjectionFsw) and the vehicle's engine with its TVC
and side jets (TvcEnginePlant), both Python SysModels (docs/guides/basilisk.md, "Python or C module").

OgkInjectionFsw, the flight software, talks only through Basilisk's standard messages:
  in   navTransInMsg (NavTransMsg: r_BN_N, v_BN_N), navAttInMsg (NavAttMsg: sigma_BN, omega_BN_B)
  out  attRefOutMsg (AttRefMsg: the commanded attitude, x_b along the thrust command, eqs. 38-39)
       cmdTorqueOutMsg (CmdTorqueBodyMsg: the side jets' roll torque command M_xc, eq. 45)
       tvcCmdOutMsg (JointArrayStateMsg: states = [Delta_yc, Delta_zc], the TVC deflection
                     commands of eq. 46, rad)
       thrOnTimeOutMsg (THRArrayOnTimeCmdMsg: OnTimeRequest[0] = time until engine cut-off, s)
Inside, one KernelFlightSoftware (ogk.missions.orbit_injection.flight_software): the kernel's
VTD-NOG, energy cut-off, terminal steering and CPD, as in ogk's own campaigns. It must run at the
scenario's control rate (SilSettings.control_rate_hz, 50 Hz): its task's period must divide the
control period (it acts on the control ticks only, and checks that it sees every one).

TvcEnginePlant is the vehicle hardware that Basilisk's library has no model of (a gimballed engine
with a time-varying thrust and first-order actuators, Pontani & Celani eqs. 16-18, 53, 55): it
reads the three commands, and writes the force and torque for an extForceTorque effector and the
hub's mass and inertia (mass depletion). Over each step [t, t + h] it applies the step averages:
the first-order actuators' exact mean under a held command, thrust, mass, arm and inertia at the
midpoint, so that the held force is second-order accurate in h (docs/guides/basilisk.md, "Tolerances").
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray
from ogk_bindings.extras import need

from ogk.missions.orbit_injection import truth as tm
from ogk.missions.orbit_injection.dispersions import ActuationNoise
from ogk.missions.orbit_injection.flight_software import KernelFlightSoftware
from ogk.missions.orbit_injection.sil import SilSettings

from . import frames

# Basilisk is the extra ogk[basilisk] (ogk_bindings.extras): one line naming it when it is missing
_BASILISK = "the Basilisk modules of ogk.missions.orbit_injection.basilisk"
messaging = need("Basilisk.architecture.messaging", "basilisk", _BASILISK)
messagingSupport = need("Basilisk.architecture.messaging.messagingSupport", "basilisk", _BASILISK)
sysModel = need("Basilisk.architecture.sysModel", "basilisk", _BASILISK)
macros = need("Basilisk.utilities.macros", "basilisk", _BASILISK)

F64 = NDArray[np.float64]
#: OnTimeRequest while the cut-off is not known yet (the engine keeps firing) [s]
ON_UNTIL_TOLD_S = 1.0e3


class OgkInjectionFsw(sysModel.SysModel):
    """ogk's orbit-injection flight software as a Basilisk module (see the module doc)."""

    def __init__(self, scn: Any, ref: Any, tables: Any, settings: SilSettings = SilSettings()
                 ) -> None:
        super().__init__()
        self.ModelTag = "ogkInjectionFsw"
        self.scenario, self.settings = scn, settings
        self._args = (scn, ref, tables)
        self.navTransInMsg = messaging.NavTransMsgReader()
        self.navAttInMsg = messaging.NavAttMsgReader()
        self.attRefOutMsg = messaging.AttRefMsg()
        self.cmdTorqueOutMsg = messaging.CmdTorqueBodyMsg()
        self.tvcCmdOutMsg = messaging.JointArrayStateMsg()
        self.thrOnTimeOutMsg = messaging.THRArrayOnTimeCmdMsg()
        self.fsw: KernelFlightSoftware | None = None
        self.failure = ""                 #: "" or sil.FAILURE_REASONS entry once failed
        self.t_cutoff_s = math.inf        #: cut-off in force [s since ignition]
        self.last_tick: Any = None        #: sil.Tick of the last control tick
        self._k = 0
        self._t0_ns: int | None = None
        self._payloads = (messaging.AttRefMsgPayload(), messaging.CmdTorqueBodyMsgPayload(),
                          messaging.JointArrayStateMsgPayload(),
                          messaging.THRArrayOnTimeCmdMsgPayload())

    def Reset(self, CurrentSimNanos: int) -> None:  # noqa: N802,N803 (Basilisk's names)
        self.fsw = KernelFlightSoftware(*self._args, np.zeros(1, dtype=np.int64), self.settings)
        self._k, self._t0_ns, self.failure, self.t_cutoff_s = 0, None, "", math.inf

    def UpdateState(self, CurrentSimNanos: int) -> None:  # noqa: N802,N803
        if self._t0_ns is None:
            self._t0_ns = CurrentSimNanos       # ignition: the first tick
        t = macros.NANO2SEC * (CurrentSimNanos - self._t0_ns)
        phase = t * self.settings.control_rate_hz
        if abs(phase - round(phase)) > 1e-6:
            return                 # a dynamics step between control ticks: commands held
        if round(phase) != self._k:
            raise RuntimeError(f"OgkInjectionFsw runs every {1.0 / self.settings.control_rate_hz:g} s"
                               f" (a multiple of its task's period): tick {self._k} is due at "
                               f"{self._k / self.settings.control_rate_hz:.6f} s, called at "
                               f"{t:.6f} s")
        if self.failure or t >= self.t_cutoff_s:
            self._write(CurrentSimNanos, None, t)
            self._k += 1
            return
        nav_t, nav_a = self.navTransInMsg(), self.navAttInMsg()
        nav = frames.ogk_from_cartesian(nav_t.r_BN_N, nav_t.v_BN_N)
        att = frames.ogk_attitude(nav_a.sigma_BN, nav_a.omega_BN_B)
        assert self.fsw is not None
        tick = self.fsw.tick(self._k, np.array([t]), nav[None, :], att[None, :],
                             np.ones(1, dtype=bool))
        self.failure = tick.failure[0]
        self.t_cutoff_s = float(tick.t_cutoff_s[0])
        self.last_tick = tick
        self._write(CurrentSimNanos, tick, t)
        self._k += 1

    def _write(self, now_ns: int, tick: Any, t: float) -> None:
        ref, torque, tvc, on = self._payloads
        if tick is not None and not self.failure:
            a = tick.attitude
            c_ba = frames.dcm_321(float(a.psi_c[0]), float(a.theta_c[0]),
                                  self.scenario.cpd.roll_command_rad)
            ref.sigma_RN = frames.sigma_bn_of(c_ba)
            torque.torqueRequestBody = [float(a.m_xc[0]), 0.0, 0.0]
            tvc.states = messagingSupport.DoubleVector([float(a.delta_yc[0]),
                                                        float(a.delta_zc[0])])
            left = self.t_cutoff_s - t
            on.OnTimeRequest = [left if math.isfinite(left) else ON_UNTIL_TOLD_S]
        else:
            torque.torqueRequestBody = [0.0, 0.0, 0.0]
            tvc.states = messagingSupport.DoubleVector([0.0, 0.0])
            on.OnTimeRequest = [0.0]
        self.attRefOutMsg.write(ref, now_ns, self.moduleID)
        self.cmdTorqueOutMsg.write(torque, now_ns, self.moduleID)
        self.tvcCmdOutMsg.write(tvc, now_ns, self.moduleID)
        self.thrOnTimeOutMsg.write(on, now_ns, self.moduleID)


class TvcEnginePlant(sysModel.SysModel):
    """The engine, TVC and side jets of Pontani & Celani (eqs. 16-18, 53, 55) for Basilisk: reads
    the FSW's commands, writes extForceTorque's body force and torque and the hub's mass
    properties (see the module doc). `thrust_coeffs` (10,) are the run's eq. (55) draws (None:
    nominal thrust); `noise` an ActuationNoise of the run (Table 5, one draw per control tick)."""

    def __init__(self, scn: Any, tf_nominal_s: float, hub: Any, step_s: float,
                 control_rate_hz: float, thrust_coeffs: F64 | None = None,
                 noise: ActuationNoise | None = None) -> None:
        super().__init__()
        self.ModelTag = "tvcEnginePlant"
        self.p = tm.TruthParams.from_scenario(scn, tf_nominal_s)
        self.hub, self.h = hub, float(step_s)
        self.coeffs = None if thrust_coeffs is None else np.asarray(thrust_coeffs)[:, None]
        self.noise_src = noise
        self._ticks_per_step = 1.0 / (control_rate_hz * self.h)
        self.tvcCmdInMsg = messaging.JointArrayStateMsgReader()
        self.cmdTorqueInMsg = messaging.CmdTorqueBodyMsgReader()
        self.thrOnTimeInMsg = messaging.THRArrayOnTimeCmdMsgReader()
        self.cmdForceOutMsg = messaging.CmdForceBodyMsg()
        self.cmdTorqueOutMsg = messaging.CmdTorqueBodyMsg()
        self.state = [0.0, 0.0, 0.0]      #: actuator states (M_x, Delta_y, Delta_z), eqs. 16, 18
        self.held_noise: tuple[float, ...] = (0.0, 0.0, 0.0)
        self.command: tuple[float, ...] = (0.0, 0.0, 0.0)
        self._every = max(1, round(self._ticks_per_step))
        self._payloads = (messaging.CmdForceBodyMsgPayload(), messaging.CmdTorqueBodyMsgPayload())
        self._mass_properties(0.5 * self.h)
        self.engine_off_s = math.inf
        self._j = 0
        self._t0_ns: int | None = None

    def Reset(self, CurrentSimNanos: int) -> None:  # noqa: N802,N803
        self.state = [0.0, 0.0, 0.0]
        self._j, self._t0_ns, self.engine_off_s = 0, None, math.inf
        self._mass_properties(0.5 * self.h)      # those of the first step [0, h]

    def _mass_properties(self, t: float) -> None:
        """Hub mass m(t) and inertia I(t) (eq. 53, or the tabulated mass)."""
        _, mass = self.p.thrust_mass(t)
        _, ix, iy, iz = tm.mass_properties(self.p, t)
        self.hub.mHub = float(mass)
        self.hub.IHubPntBc_B = [[float(ix), 0.0, 0.0], [0.0, float(iy), 0.0],
                                [0.0, 0.0, float(iz)]]

    def thrust(self, t: float) -> float:
        """T(t) [1 + f(t)] [N] (sec. 6, eq. 55; tabulated: sec. 7)."""
        nominal, _ = self.p.thrust_mass(t)
        if self.coeffs is None:
            return float(nominal)
        return float(nominal) * float(tm.thrust_factor(self.p, t, self.coeffs)[0])

    def UpdateState(self, CurrentSimNanos: int) -> None:  # noqa: N802,N803
        if self._t0_ns is None:
            self._t0_ns = CurrentSimNanos
        t = macros.NANO2SEC * (CurrentSimNanos - self._t0_ns)
        self.step(t, self.h, CurrentSimNanos)

    def step(self, t: float, h: float, now_ns: int) -> None:
        """Commands read at t (at control ticks), averages over [t, t + h] written (h: the step
        the dynamics take next; the last step of a burn is shortened onto the cut-off)."""
        if self._j % self._every == 0:
            # a control tick: new commands, and a new held actuation-noise draw (eq. 17)
            tvc, torque = self.tvcCmdInMsg(), self.cmdTorqueInMsg()
            states = tvc.states
            self.command = (float(torque.torqueRequestBody[0]), float(states[0]),
                            float(states[1]))
            self.engine_off_s = t + float(self.thrOnTimeInMsg().OnTimeRequest[0])
            if self.noise_src is not None:
                self.held_noise = tuple(float(v) for v in self.noise_src.next()[:, 0])
        self._j += 1
        # the last step of the burn ends at the cut-off: averages over [t, t_off] only
        h = min(h, self.engine_off_s - t)
        if h <= 0.0:
            self._write_zero(now_ns)
            return
        out = []
        for i in range(3):
            tau, u, x = self.p.time_constant[i], self.command[i], self.state[i]
            decay = math.exp(-h / tau)
            # exact mean of x' = (u - x) / tau over the step under the held command u (eqs. 16,
            # 18), then sat(mean + noise) (eq. 17)
            mean = u + (x - u) * (tau / h) * (1.0 - decay)
            self.state[i] = u + (x - u) * decay
            lim = self.p.output_max[i]
            out.append(min(max(mean + self.held_noise[i], -lim), lim))
        mx, dy, dz = out
        t_mid = t + 0.5 * h
        thrust = self.thrust(t_mid)
        arm = self.p.arm0 + self.p.arm_rate * t_mid
        # Basilisk's Spacecraft integrates the step [t, t + h] with the hub mass properties in
        # force when the previous step ended (measured in docs/guides/basilisk.md: a value set during
        # step k acts in step k + 1), so this step sets those of the next: its midpoint
        self._mass_properties(t_mid + self.h)
        cdz = math.cos(dz)
        d_b = (cdz * math.cos(dy), math.sin(dz), cdz * math.sin(dy))
        force, torque_out = self._payloads
        force.forceRequestBody = [thrust * d_b[0], thrust * d_b[1], thrust * d_b[2]]
        # nozzle at -l x_b: (-l x_b) x (T d_b) = T l (0, d_b3, -d_b2), eqs. 14-15; side jets M_x
        torque_out.torqueRequestBody = [mx, thrust * arm * d_b[2], -thrust * arm * d_b[1]]
        self.cmdForceOutMsg.write(force, now_ns, self.moduleID)
        self.cmdTorqueOutMsg.write(torque_out, now_ns, self.moduleID)

    def _write_zero(self, now_ns: int) -> None:
        """Engine off: no force, no torque."""
        self.cmdForceOutMsg.write(messaging.CmdForceBodyMsgPayload(), now_ns, self.moduleID)
        self.cmdTorqueOutMsg.write(messaging.CmdTorqueBodyMsgPayload(), now_ns, self.moduleID)
