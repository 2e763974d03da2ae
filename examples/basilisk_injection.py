"""ogk's orbit-injection flight software as a module of your own Basilisk simulation.

    .venv/bin/python examples/basilisk_injection.py [SCENARIO] [--compare N] [--seed S]

Builds a plain Basilisk simulation (a Spacecraft hub, Earth's point-mass gravity, simpleNav, an
extForceTorque effector), drops in ogk's flight software (OgkInjectionFsw: VTD-NOG + end-game + CPD,
reading NavTransMsg/NavAttMsg, writing AttRefMsg, CmdTorqueBodyMsg, the TVC commands and the engine
on-time) and the vehicle's engine and actuators (TvcEnginePlant), flies the nominal burn to engine
cut-off and prints the injection errors. With --compare N it then flies N dispersed runs in both
Basilisk and ogk's own 6-DOF truth model and prints both sets of statistics (docs/guides/basilisk.md).
"""
from __future__ import annotations

import argparse
import math
import sys

from Basilisk.simulation import extForceTorque, simpleNav, spacecraft
from Basilisk.utilities import SimulationBaseClass, macros, simIncludeGravBody

from ogk.missions.orbit_injection.basilisk import frames
from ogk.missions.orbit_injection.basilisk.crosscheck import main as crosscheck_main
from ogk.missions.orbit_injection.basilisk.modules import OgkInjectionFsw, TvcEnginePlant
from ogk.missions.orbit_injection import truth as tm
from ogk.missions.orbit_injection.dispersions import DispersionSwitches, draw_runs
from ogk.missions.orbit_injection.nog_guidance import prepare_tables
from ogk.missions.orbit_injection.nominal_ref import resolved_with_reference
from ogk.missions.orbit_injection.sil import SilSettings, initial_state
from ogk_host.orbit_injection.scenario import load_scenario


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario", nargs="?", default="scenarios/leo_geo.toml")
    ap.add_argument("--compare", type=int, default=0, metavar="N",
                    help="then fly N dispersed runs in Basilisk and in ogk's truth model")
    ap.add_argument("--seed", type=int, default=7)
    args = ap.parse_args()

    # ogk's ground products: the scenario, its nominal and its VTD-NOG tables (made when missing)
    scn, ref = resolved_with_reference(load_scenario(args.scenario))
    tables = prepare_tables(scn)
    settings = SilSettings()                      # 50 Hz control, the scenario's end-game
    dt_ns = macros.sec2nano(settings.truth_step_s)

    # your Basilisk simulation: one process, one 20 ms task
    sim = SimulationBaseClass.SimBaseClass()
    sim.CreateNewProcess("main").addTask(sim.CreateNewTask("loop", dt_ns))
    sc = spacecraft.Spacecraft()
    sc.ModelTag = "upperStage"
    gravity = simIncludeGravBody.gravBodyFactory()
    earth = gravity.createEarth()
    earth.isCentralBody = True
    earth.mu = scn.mu_m3_s2
    gravity.addBodiesTo(sc)
    # ignition state: the scenario's nominal (ogk's coordinates -> Basilisk's N frame)
    draws, _ = draw_runs(scn, 0, [0], DispersionSwitches.none())
    x0 = initial_state(scn, ref, draws, "6dof")[:, 0]
    r_n, v_n = frames.cartesian_from_ogk(x0[:6])
    sc.hub.r_CN_NInit = [[float(v)] for v in r_n]
    sc.hub.v_CN_NInit = [[float(v)] for v in v_n]
    sc.hub.sigma_BNInit = [[v] for v in frames.sigma_bn_of(tm.dcm_from_quat(x0[6:10]))]
    nav = simpleNav.SimpleNav()
    nav.scStateInMsg.subscribeTo(sc.scStateOutMsg)
    engine = extForceTorque.ExtForceTorque()
    sc.addDynamicEffector(engine)

    # ogk's flight software, and the vehicle's engine, TVC and side jets
    fsw = OgkInjectionFsw(scn, ref, tables, settings)
    fsw.navTransInMsg.subscribeTo(nav.transOutMsg)
    fsw.navAttInMsg.subscribeTo(nav.attOutMsg)
    plant = TvcEnginePlant(scn, ref.tf_s, sc.hub, settings.truth_step_s, settings.control_rate_hz)
    plant.tvcCmdInMsg.subscribeTo(fsw.tvcCmdOutMsg)
    plant.cmdTorqueInMsg.subscribeTo(fsw.cmdTorqueOutMsg)
    plant.thrOnTimeInMsg.subscribeTo(fsw.thrOnTimeOutMsg)
    engine.cmdForceBodyInMsg.subscribeTo(plant.cmdForceOutMsg)
    engine.cmdTorqueInMsg.subscribeTo(plant.cmdTorqueOutMsg)
    for model, priority in ((sc, 100), (nav, 90), (fsw, 80), (plant, 70), (engine, 60)):
        sim.AddModelToTask("loop", model, priority)

    # fly until the flight software's cut-off falls within the next step, then land on it
    sim.InitializeSimulation()
    k = 0
    while True:
        sim.ConfigureStopTime(k * dt_ns)
        sim.ExecuteSimulation()
        if fsw.failure:
            print(f"flight software failure: {fsw.failure}")
            return 1
        if fsw.t_cutoff_s - k * settings.truth_step_s <= settings.truth_step_s:
            break
        k += 1
    sc.UpdateState(int(round(fsw.t_cutoff_s * 1e9)))   # the last, partial step
    state = sc.scStateOutMsg.read()
    r, _, phi, v_r, v_t, v_n = frames.ogk_from_cartesian(state.r_BN_N, state.v_BN_N)
    v_c = math.sqrt(scn.mu_m3_s2 / scn.target_radius_m)
    print(f"{scn.name} in Basilisk, ogk in the loop: cut-off t_f = {fsw.t_cutoff_s:.3f} s, "
          f"dr_f = {r - scn.target_radius_m:.3f} m, dphi_f = {math.degrees(phi):.2e} deg, "
          f"dv_rf = {v_r:.4f} m/s, dv_tf = {v_t - v_c:.4f} m/s, dv_nf = {v_n:.4f} m/s")
    if args.compare:
        return crosscheck_main([args.scenario, "--seed", str(args.seed), "--runs",
                                str(args.compare)])
    return 0


if __name__ == "__main__":
    sys.exit(main())
