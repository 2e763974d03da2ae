"""The flight code's NMPC (ogk_nmpc, kernel/include/ogk/nmpc.h) against independent references:

- its predictive model against the ground's numpy model (ogk_host.rendezvous.dynamics: eqs. 11-14, third
  bodies from Cartesian vectors), for the nuclear- and solar-electric engines;
- one shooting interval against the numpy RK4 twin (dynamics.rk4_interval) and its sensitivities against
  central differences through the bindings; its multiplier-weighted second derivatives (the exact SQP
  Hessian's block) against CasADi's algorithmic Hessian of the ground NLP's own interval map;
- the open loop of the same transcription against CasADi + IPOPT (RendezvousNlp): minimum time (t_f*) and
  bounded-thrust minimum fuel (the fuel), and the kernel's plan re-integrated by scipy's DOP853;
- the unperturbed SNNS closed loop (Table I's column) reaching Mars before the open loop's t_f*, with the
  fuel of the nominal mass flow, and a perturbed flight on a seed reserved for this test (101).
"""
from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ogk_host.rendezvous.dynamics import DAY_S, Engine, Model, planets, rk4_interval, third_body_accel, throttle_rhs
from ogk_host.rendezvous.nlp import RendezvousNlp, min_fuel_guess, min_time_guess
from ogk_host.rendezvous.scenario import load_scenario, paper_problem

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.kernel import KernelError
from ogk_bindings.nmpc import Nmpc
from ogk.missions.rendezvous.closed_loop import fly_run
from ogk.missions.rendezvous.guidance_base import first_guess, strategy_settings
from ogk.missions.rendezvous.kernel_guidance import KernelGuidance, kernel_config

MIN_TIME = "scenarios/rendezvous_nep_min_time.toml"
NEP_FUEL = "scenarios/rendezvous_nep_min_fuel.toml"
SEP_FUEL = "scenarios/rendezvous_sep_min_fuel.toml"


def kernel_for(path: str, **overrides: object) -> tuple[Nmpc, object]:
    """The kernel on the paper's problem (the ground NLP's: no robustness options, no propellant row)."""
    scen = paper_problem(load_scenario(path))
    overrides.setdefault("mass_min", 0.0)
    return Nmpc(kernel_config(scen, strategy_settings(scen, "snns"), **overrides)), scen


@pytest.mark.req("OGK-NMPC-001")
@pytest.mark.parametrize("path", [MIN_TIME, NEP_FUEL, SEP_FUEL])
def test_model_matches_the_ground_model(path: str) -> None:
    g, scen = kernel_for(path, third_bodies=True)
    engine = Engine.for_scenario(scen)
    bodies = planets(scen, mars_softening_m=scen.convergence.target_soi_radius_m)
    rng = np.random.default_rng(7)
    for _ in range(20):
        x = np.array([rng.uniform(0.8, 1.6), rng.uniform(-3, 6), rng.normal(0, 0.1), rng.uniform(0.7, 1.1),
                      rng.uniform(0.5, 1.0)])
        t = rng.uniform(0, 12)
        u = np.array([rng.uniform(-4, 4), rng.uniform(0, 1)])[: g.nu]
        w = u[1] if g.nu == 2 else 1.0
        ref = throttle_rhs(x, u[0], w, engine)
        a_r, a_t = third_body_accel(t, x[0], x[1], bodies)
        ref[2] += a_r
        ref[3] += a_t
        np.testing.assert_allclose(g.model_rhs(t, x, u), ref, rtol=1e-12, atol=1e-14)


@pytest.mark.req("OGK-NMPC-002")
def test_interval_matches_numpy_rk4_and_finite_differences() -> None:
    g, scen = kernel_for(MIN_TIME)
    model = Model.for_scenario(scen)
    x0 = np.array([1.05, 0.3, 0.02, 0.97, 0.9])
    x1, dfdx, dfdu0, dfdu1, dfdh, dfdt0 = g.interval(0.4, 0.21, x0, [0.5], [2.1])
    ref = rk4_interval(x0, 0.5, 2.1, 0.21, int(scen.nmpc.rk4_steps_per_interval), model.thrust, model.mass_flow)
    np.testing.assert_allclose(x1, ref, rtol=1e-14, atol=1e-15)
    eps = 1e-6
    for j in range(5):
        e = np.zeros(5)
        e[j] = eps
        fd = (g.interval(0.4, 0.21, x0 + e, [0.5], [2.1])[0] - g.interval(0.4, 0.21, x0 - e, [0.5], [2.1])[0]) / (2 * eps)
        np.testing.assert_allclose(dfdx[:, j], fd, atol=1e-8)
    fd_u1 = (g.interval(0.4, 0.21, x0, [0.5], [2.1 + eps])[0] - g.interval(0.4, 0.21, x0, [0.5], [2.1 - eps])[0]) / (2 * eps)
    np.testing.assert_allclose(dfdu1[:, 0], fd_u1, atol=1e-8)
    fd_h = (g.interval(0.4, 0.21 + eps, x0, [0.5], [2.1])[0] - g.interval(0.4, 0.21 - eps, x0, [0.5], [2.1])[0]) / (2 * eps)
    np.testing.assert_allclose(dfdh, fd_h, atol=1e-8)
    np.testing.assert_allclose(dfdt0, 0.0, atol=0.0)   # no third body: autonomous
    assert np.max(np.abs(dfdu0)) > 1e-3


@pytest.mark.req("OGK-NMPC-002")
@pytest.mark.parametrize("path,bodies", [(MIN_TIME, False), (SEP_FUEL, True)])
def test_interval_second_derivatives_match_casadi(path: str, bodies: bool) -> None:
    """sum_i w_i d2F_i/dp2, p = (x, u0, u1, h, t0): the kernel's forward-over-adjoint sweep against CasADi's
    exact Hessian of RendezvousNlp's interval (the same RK4 transcription; SEP: solar engine, throttle,
    Earth and Mars in the model)."""
    g, scen = kernel_for(path, third_bodies=bodies)
    nlp = RendezvousNlp(scen, rk4_steps=scen.nmpc.rk4_steps_per_interval, third_bodies=bodies)
    nu = g.nu
    n = 5 + 2 * nu + 2
    p = ca.SX.sym("p", n)
    w = np.array([0.7, -1.3, 2.1, 0.4, -0.9])
    xf = nlp._interval(p[:5], p[5:5 + nu], p[5 + nu:5 + 2 * nu], p[5 + 2 * nu], p[6 + 2 * nu])
    hess_ref = ca.Function("h", [p], [ca.hessian(ca.dot(ca.DM(w), xf), p)[0]])
    rng = np.random.default_rng(11)
    for _ in range(3):
        x0 = np.array([rng.uniform(1.0, 1.5), rng.uniform(0, 3), rng.normal(0, 0.05), rng.uniform(0.8, 1.0),
                       rng.uniform(0.6, 1.0)])
        u0 = np.array([rng.uniform(-3, 3), rng.uniform(0.1, 0.9)])[:nu]
        u1 = np.array([rng.uniform(-3, 3), rng.uniform(0.1, 0.9)])[:nu]
        h, t0 = rng.uniform(0.1, 0.3), rng.uniform(0, 6)
        ref = np.asarray(hess_ref(np.concatenate([x0, u0, u1, [h, t0]])))
        out = np.empty(n * n)
        arrays = [np.ascontiguousarray(a, dtype=np.float64) for a in (x0, u0, u1, w)]
        status = lib.ogk_nmpc_interval_hess(g._ctx, float(t0), float(h),
                                            *[ffi.from_buffer("double[]", a) for a in arrays],
                                            ffi.from_buffer("double[]", out))
        assert status == 0
        np.testing.assert_allclose(out.reshape(n, n), ref, rtol=1e-9, atol=1e-11 * np.max(np.abs(ref)))
        assert np.max(np.abs(ref)) > 1e-2


def reintegrate_miss(scen, plan) -> tuple[float, float]:
    """DOP853 flight of the plan's piecewise-linear control; miss to eq. (5) at t_f in km, m/s."""
    model = Model.for_scenario(scen)
    engine = Engine.for_scenario(scen)

    def rhs(t: float, x: np.ndarray) -> np.ndarray:
        u = plan_control(plan, t)
        return throttle_rhs(x, u[0], u[1] if u.shape[0] > 1 else 1.0, engine)

    sol = solve_ivp(rhs, (plan.t0, plan.t0 + plan.horizon), plan.states[0], method="DOP853", rtol=1e-12,
                    atol=1e-13, t_eval=None)
    xf = sol.y[:, -1]
    mars = model.mars_state(plan.t0 + plan.horizon)
    r, th, vr, vt = xf[:4]
    rm, thm, _, vm = mars
    dpos = math.hypot(r * math.cos(th) - rm * math.cos(thm), r * math.sin(th) - rm * math.sin(thm))
    dvel = math.hypot(vr, vt - vm)
    return dpos * model.units.length_m / 1e3, dvel * model.units.velocity_m_s


def plan_control(plan, t: float) -> np.ndarray:
    s = min(max((t - plan.t0) / (plan.horizon / plan.nodes), 0.0), plan.nodes)
    k = min(int(s), plan.nodes - 1)
    f = s - k
    return (1 - f) * plan.controls[k] + f * plan.controls[k + 1]


class _P:
    def __init__(self, p) -> None:  # type: ignore[no-untyped-def]
        self.t0, self.horizon, self.states, self.controls = p.t0, p.horizon, p.states, p.controls
        self.nodes = p.states.shape[0] - 1


@pytest.mark.req("OGK-NMPC-003")
def test_open_loop_min_time_equals_ipopt_and_reintegrates() -> None:
    g, scen = kernel_for(MIN_TIME, tol_stat=1e-9, tol_obj=0.0)
    x0 = Model.for_scenario(scen).x0
    guess = first_guess(scen, scen.ocp.nodes, 0.0, x0, g.nu)
    g.load_plan(guess.t0, guess.horizon, guess.states, guess.controls)
    rep = g.solve(0.0, x0)
    assert rep.converged, rep.status
    days = Model.for_scenario(scen).units.time_s / DAY_S
    nlp = RendezvousNlp(scen, rk4_steps=scen.nmpc.rk4_steps_per_interval)
    ref = nlp.solve(0.0, x0, min_time_guess(nlp))
    assert ref.converged
    assert rep.t_f * days <= 370.3                       # issue 10: at most 370.3 d (paper 370.29)
    assert abs(rep.t_f - ref.plan.t_f) * days < 1e-4     # the same optimum of the same transcription
    dpos_km, dvel = reintegrate_miss(scen, _P(g.plan()))
    assert dpos_km < 100.0 and dvel < 0.01               # the RK4 error of docs/design/nmpc.md (30 km, 2.4 mm/s)


@pytest.mark.req("OGK-NMPC-003")
def test_exact_hessian_open_loop_reaches_ipopt_at_the_default_tolerance() -> None:
    """The exact Hessian (OGK_NMPC_HESSIAN_EXACT) at the kernel's default tol_obj lands on IPOPT's optimum of
    the same transcription within 1 s of t_f (BFGS needs tol_obj = 0 and more iterations for that: 127
    against 78 when measured; the cold start's non-convex iterations take identity steps)."""
    exact = int(lib.OGK_NMPC_HESSIAN_EXACT)
    g, scen = kernel_for(MIN_TIME, hessian=exact)
    x0 = Model.for_scenario(scen).x0
    guess = first_guess(scen, scen.ocp.nodes, 0.0, x0, g.nu)
    g.load_plan(guess.t0, guess.horizon, guess.states, guess.controls)
    rep = g.solve(0.0, x0)
    assert rep.converged, rep.status
    nlp = RendezvousNlp(scen, rk4_steps=scen.nmpc.rk4_steps_per_interval)
    ref = nlp.solve(0.0, x0, min_time_guess(nlp))
    assert ref.converged
    time_s = Model.for_scenario(scen).units.time_s
    assert abs(rep.t_f - ref.plan.t_f) * time_s < 1.0
    assert rep.feas <= 1e-9
    bfgs, _ = kernel_for(MIN_TIME, tol_obj=0.0)
    bfgs.load_plan(guess.t0, guess.horizon, guess.states, guess.controls)
    rep_bfgs = bfgs.solve(0.0, x0)
    assert rep_bfgs.converged
    assert rep.sqp_iterations < rep_bfgs.sqp_iterations


@pytest.mark.req("OGK-NMPC-003")
def test_open_loop_min_fuel_equals_ipopt_fuel() -> None:
    scen = paper_problem(load_scenario(NEP_FUEL))
    x0 = Model.for_scenario(scen).x0
    guess, _ = min_fuel_guess(scen)                      # the min-time optimum at full throttle
    g = Nmpc(kernel_config(scen, strategy_settings(scen, "snns"), time_weight=0.0, mass_min=0.0))   # the paper J
    g.load_plan(guess.t0, guess.horizon, guess.states, guess.controls)
    rep = g.solve(0.0, x0)
    assert rep.converged, rep.status
    nlp = RendezvousNlp(scen, rk4_steps=scen.nmpc.rk4_steps_per_interval)
    ref = nlp.solve(0.0, x0, guess)
    assert ref.converged
    mu = Model.for_scenario(scen).units.mass_kg
    # fuel is flat in t_f along the coast: compare the fuel, not t_f; the kernel stops when a step predicts
    # |dJ| <= 1e-7 (tol_obj), which leaves it within ~0.1 kg on this flat valley (docs/design/nmpc-flight.md)
    assert abs(rep.objective - (1.0 - ref.plan.states[-1, 4])) * mu < 0.2
    w = g.plan().controls[:, 1]
    assert np.all((w >= 0.0) & (w <= 1.0)) and np.any(w < 0.05) and np.any(w > 0.95)


@pytest.mark.req("OGK-NMPC-010")
def test_unperturbed_snns_closed_loop_reaches_mars_before_the_open_loop() -> None:
    # the paper's problem (no robustness options): its 353.37 d is the first instant inside Mars' SOI,
    # ~17 d before t_f* = 370.12 d
    scen = paper_problem(load_scenario(MIN_TIME))
    r = fly_run(scen, KernelGuidance(scen, strategy_settings(scen, "snns")), perturbed=False, seed=0)
    assert r.converged and r.reason == "rendezvous"
    assert r.failed_solves == 0
    assert 345.0 < r.t_f_days < 360.0
    mdot = scen.propulsion.mass_flow_at_max_kg_s
    assert r.fuel_kg == pytest.approx(mdot * r.t_f_days * DAY_S, rel=1e-6)
    # the shipped law (12 % thrust margin, terminal set, Earth while departing): the same engine arrives
    # before its own first plan's t_f, which its margin makes later than the paper's
    law = load_scenario(MIN_TIME)
    g = KernelGuidance(law, strategy_settings(law, "snns"))
    r = fly_run(law, g, perturbed=False, seed=0)
    assert r.converged and r.failed_solves == 0
    assert r.history[0].planned_t_f_days > 370.12
    assert r.t_f_days < r.history[0].planned_t_f_days
    assert r.fuel_kg == pytest.approx(mdot * r.t_f_days * DAY_S, rel=1e-6)


@pytest.mark.req("OGK-NMPC-010")
def test_perturbed_snns_closed_loop_on_its_own_seed() -> None:
    scen = load_scenario(MIN_TIME)
    r = fly_run(scen, KernelGuidance(scen, strategy_settings(scen, "snns")), perturbed=True, seed=101)
    assert r.converged
    assert r.final_position_miss_km < scen.convergence.target_soi_radius_m / 1e3


@pytest.mark.req("OGK-NMPC-008")
def test_bad_inputs_raise() -> None:
    g, scen = kernel_for(MIN_TIME)
    with pytest.raises(KernelError):
        g.solve(0.0, [1.0, 0.0, 0.0, 1.0, 1.0])          # no plan yet
    with pytest.raises(KernelError):
        g.command(float("nan"))
    with pytest.raises(ValueError):
        g.load_plan(0.0, 6.0, np.zeros((40, 5)), np.zeros((40, 1)))
