"""Kernel RK4 switch location on the minimum-fuel double integrator (harness C model):
located switching times and states vs the closed-form bang-off-bang solution.

Rest-to-rest transfer of distance D in time T with |u| <= u_max: thrust +u_max on
[0, t1], coast on [t1, t2], thrust -u_max on [t2, T], with
t1 = (T - sqrt(T^2 - 4 D/u_max))/2 and t2 = T - t1 (coded again below, independently
of ogk_bindings.models.RestToRest). Between switches the motion is a quadratic and the
costates linear in t, which RK4 integrates exactly, so the errors measure the
bisection alone."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ogk_bindings import kernel, models
from ogk_bindings._ffi import lib

CASES = [  # D, T, u_max, h
    (1.0, 3.0, 1.0, 0.1),
    (1.0, 3.0, 1.0, 0.07),
    (2.5, 4.0, 0.9, 0.25),
    (100.0, 30.0, 0.45, 1.0),
    (100.0, 30.0, 0.5, 1.0),   # t1 = 10 and t2 = 20 exactly on grid points
    (1.0, 3.0, 1.0, 0.5),
]


def closed_form(D: float, T: float, u: float, t: float) -> np.ndarray:
    t1 = (T - math.sqrt(T * T - 4.0 * D / u)) / 2.0
    t2 = T - t1
    if t <= t1:
        r, v = 0.5 * u * t * t, u * t
    elif t <= t2:
        r, v = 0.5 * u * t1 * t1 + u * t1 * (t - t1), u * t1
    else:
        r, v = D - 0.5 * u * (T - t) ** 2, u * (T - t)
    # lambda_v linear from -T/(T - 2 t1) through -1 at t1 and +1 at t2.
    lam_r = -2.0 / (T - 2.0 * t1)
    lam_v = -T / (T - 2.0 * t1) - lam_r * t
    return np.array([r, v, lam_r, lam_v])


def switch_times(D: float, T: float, u: float) -> tuple[float, float]:
    t1 = (T - math.sqrt(T * T - 4.0 * D / u)) / 2.0
    return t1, T - t1


@pytest.mark.req("OGK-CORE-014")
@pytest.mark.parametrize("D, T, u, h", CASES)
def test_switch_times_and_states(D: float, T: float, u: float, h: float) -> None:
    x0 = closed_form(D, T, u, 0.0)
    res = kernel.rk4_propagate(models.min_fuel_double_integrator(u), x0, 0.0, T, h, mode0=1,
                               s_tol=1e-14, t_tol=1e-15, dense_capacity=1000)
    t_exact = switch_times(D, T, u)
    assert [e.mode_after for e in res.switches] == [0, 1]
    assert res.mode_final == 1 and res.t_reached == T
    for event, t_ex in zip(res.switches, t_exact):
        assert abs(event.t - t_ex) < 1e-10, (event, t_ex)
        assert (event.how == lib.OGK_SWITCH_BY_S_TOL and abs(event.s) <= 1e-14) or event.by_time_tol
    # The dense grid holds each switch once, at its dense_index, with the new mode;
    # the node before it carries the old mode.
    dense = res.dense
    assert dense is not None
    assert np.all(np.diff(dense.t) > 0.0)
    for event in res.switches:
        i = event.dense_index
        assert dense.t[i] == event.t
        assert dense.mode[i] == event.mode_after and dense.mode[i - 1] == 1 - event.mode_after
    # Every node, the switch points and tf included, lies on the exact solution:
    # 1e-10 relative to the state's size (1e-10 absolute below 1).
    for t, x in zip(dense.t, dense.x):
        exact = closed_form(D, T, u, t)
        assert np.all(np.abs(x - exact) <= 1e-10 * np.maximum(1.0, np.abs(exact))), (t, x, exact)
    assert np.array_equal(dense.x[-1], res.xf)
    assert abs(res.xf[0] - D) <= 1e-10 * D and abs(res.xf[1]) <= 1e-10 * max(1.0, D)

@pytest.mark.req("OGK-CORE-014")
def test_switch_on_a_grid_point_not_double_counted() -> None:
    """h chosen so that t1 is (to rounding) a grid point: still exactly two switches."""
    D, T, u = 1.0, 3.0, 1.0
    t1, _ = switch_times(D, T, u)
    res = kernel.rk4_propagate(models.min_fuel_double_integrator(u), closed_form(D, T, u, 0.0),
                               0.0, T, t1 / 3.0, mode0=1, s_tol=1e-14, t_tol=1e-15)
    assert [e.mode_after for e in res.switches] == [0, 1]
    for event, t_ex in zip(res.switches, switch_times(D, T, u)):
        assert abs(event.t - t_ex) < 1e-10


@pytest.mark.req("OGK-CORE-014")
def test_without_switch_function_no_events() -> None:
    """Same model, switching disabled: thrust stays on; r = u t^2/2 exactly."""
    model = models.min_fuel_double_integrator(1.0)
    bare = kernel.CModel(name="no switch", n=model.n, rhs=model.rhs, user=model.user)
    res = kernel.rk4_propagate(bare, closed_form(1.0, 3.0, 1.0, 0.0), 0.0, 1.0, 0.1, mode0=1)
    assert res.switches == ()
    assert res.xf[0] == pytest.approx(0.5, abs=1e-14)
    assert res.xf[1] == pytest.approx(1.0, abs=1e-14)


@pytest.mark.req("OGK-CORE-014", "OGK-HAR-013")
def test_demo_reports_closed_form_agreement() -> None:
    from ogk.demos.switching import format_report, run_switching_demo

    demo = run_switching_demo()
    assert demo.ok(1e-10)
    np.testing.assert_allclose(demo.t_exact, switch_times(1.0, 3.0, 1.0), rtol=1e-15)
    text = format_report(demo)
    assert "closed form" in text and "final state" in text


@pytest.mark.req("OGK-CORE-014")
def test_bad_switch_tolerances() -> None:
    model = models.min_fuel_double_integrator(1.0)
    for s_tol, t_tol in [(-1.0, 1e-12), (1e-12, 0.0), (np.nan, 1e-12)]:
        with pytest.raises(kernel.KernelError) as info:
            kernel.rk4_propagate(model, closed_form(1.0, 3.0, 1.0, 0.0), 0.0, 3.0, 0.1,
                                 mode0=1, s_tol=s_tol, t_tol=t_tol)
        assert info.value.code == lib.OGK_E_RANGE


def oscillator_crossings(omega: float, h: float, n_cross: int) -> tuple[np.ndarray, kernel.Rk4Result]:
    t_exact = (np.arange(n_cross) + 0.5) * np.pi / omega
    tf = (n_cross + 0.25) * np.pi / omega  # between crossing n_cross - 1 and n_cross
    res = kernel.rk4_propagate(models.oscillator(omega), [1.0, 0.0], 0.0, tf, h,
                               s_tol=1e-15, t_tol=1e-14)
    return t_exact, res


@pytest.mark.req("OGK-CORE-014")
def test_oscillator_crossings_fourth_order() -> None:
    """q = cos(omega t) crosses zero at (k + 1/2) pi / omega; on smooth motion the located
    times carry the RK4 phase error, O(h^4): halving h divides it by ~16."""
    omega, n_cross = 2.0, 12
    errors = []
    # RK4's phase error per step on an oscillator is (omega h)^5 / 120 [rad].
    h_fine = 0.01
    t_last = (n_cross - 0.5) * np.pi / omega
    phase_bound = (omega * h_fine) ** 5 / 120.0 * (t_last / h_fine) / omega
    for h in (2 * h_fine, h_fine):
        t_exact, res = oscillator_crossings(omega, h, n_cross)
        assert [e.mode_after for e in res.switches] == [1, 0] * (n_cross // 2)
        errors.append(np.max(np.abs([e.t for e in res.switches] - t_exact)))
    assert errors[1] < 1.5 * phase_bound, (errors, phase_bound)
    assert 13.0 < errors[0] / errors[1] < 19.0, errors


@pytest.mark.req("OGK-CORE-014")
def test_switch_overflow_keeps_partial_result() -> None:
    """More crossings than OGK_RK4_MAX_SWITCHES: OGK_E_SWITCH_OVERFLOW, the stored
    events intact and the propagation stopped at the first switch that did not fit."""
    omega, max_sw = 1.0, int(lib.OGK_RK4_MAX_SWITCHES)
    with pytest.raises(kernel.KernelError) as info:
        oscillator_crossings(omega, 0.01, max_sw + 5)
    assert info.value.code == lib.OGK_E_SWITCH_OVERFLOW
    partial = info.value.partial
    assert len(partial.switches) == max_sw
    t_exact = (np.arange(max_sw + 1) + 0.5) * np.pi / omega
    np.testing.assert_allclose([e.t for e in partial.switches], t_exact[:-1], atol=1e-7)
    assert partial.t_reached == pytest.approx(t_exact[-1], abs=1e-7)
    assert abs(partial.xf[0]) < 1e-12  # q = 0 at the crossing it stopped on
