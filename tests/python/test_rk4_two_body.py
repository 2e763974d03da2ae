"""Kernel RK4 on the two-body problem (harness C model) over one orbit, e = 0.3,
against scipy solve_ivp DOP853 at rtol 1e-12 and against the exact periodicity
x(T) = x(0); checks fourth-order convergence (error ratio ~16 for h/2)."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ogk_bindings import kernel, models
from ogk_bindings._ffi import lib

MU = 1.0            # normalised units: mu = 1, a = 1, period 2 pi
SMA = 1.0
ECC = 0.3
PERIOD = 2.0 * np.pi * np.sqrt(SMA**3 / MU)


def periapsis_state() -> np.ndarray:
    """Periapsis on an orbit inclined 0.2 rad about the x axis."""
    r_p = SMA * (1.0 - ECC)
    v_p = np.sqrt(MU * (1.0 + ECC) / r_p)
    incl = 0.2
    return np.array([r_p, 0.0, 0.0, 0.0, v_p * np.cos(incl), v_p * np.sin(incl)])


def two_body_numpy(t: float, x: np.ndarray) -> np.ndarray:
    r = x[:3]
    return np.concatenate([x[3:], -MU * r / np.linalg.norm(r) ** 3])


@pytest.fixture(scope="module")
def reference():  # type: ignore[no-untyped-def]
    x0 = periapsis_state()
    sol = solve_ivp(two_body_numpy, (0.0, PERIOD), x0, method="DOP853", rtol=1e-12,
                    atol=1e-14, dense_output=True)
    assert sol.success
    assert np.max(np.abs(sol.y[:, -1] - x0)) < 1e-9  # the reference itself closes the orbit
    return sol


def propagate(n_steps: int) -> kernel.Rk4Result:
    return kernel.rk4_propagate(models.two_body(MU), periapsis_state(), 0.0, PERIOD,
                                PERIOD / n_steps, dense_capacity=n_steps + 2)


@pytest.mark.req("OGK-CORE-013")
def test_one_orbit_fourth_order(reference) -> None:  # type: ignore[no-untyped-def]
    errors = {}
    for n in (400, 800):
        res = propagate(n)
        assert res.t_reached == PERIOD and res.n_steps == n and res.n_rhs == 4 * n
        assert res.switches == () and res.dense is not None
        dense = res.dense
        assert dense.t.size == n + 1
        np.testing.assert_allclose(dense.t, np.linspace(0.0, PERIOD, n + 1), rtol=0, atol=1e-12)
        assert np.array_equal(dense.x[-1], res.xf)
        # Largest state error anywhere along the orbit, vs the DOP853 reference.
        errors[n] = float(np.max(np.abs(dense.x - reference.sol(dense.t).T)))
        # Exact truth at t = T: the orbit closes on itself.
        assert np.max(np.abs(res.xf - periapsis_state())) < 2.0 * errors[n]
    ratio = errors[400] / errors[800]
    assert 14.0 < ratio < 18.5, f"error ratio {ratio:.2f} not fourth order ({errors})"
    assert errors[800] < 2e-8, errors


@pytest.mark.req("OGK-CORE-013")
def test_energy_drift_small() -> None:
    res = propagate(800)
    assert res.dense is not None
    r = np.linalg.norm(res.dense.x[:, :3], axis=1)
    v = np.linalg.norm(res.dense.x[:, 3:], axis=1)
    energy = 0.5 * v**2 - MU / r
    assert np.max(np.abs(energy + MU / (2.0 * SMA))) < 1e-8


def textbook_rk4_step(f, t: float, x: np.ndarray, h: float) -> np.ndarray:  # type: ignore[no-untyped-def]
    k1 = f(t, x)
    k2 = f(t + h / 2, x + h / 2 * k1)
    k3 = f(t + h / 2, x + h / 2 * k2)
    k4 = f(t + h, x + h * k3)
    return x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


@pytest.mark.req("OGK-CORE-013")
@pytest.mark.parametrize("dt", [0.01, 0.3, -0.2])
def test_single_step_matches_textbook_rk4(dt: float) -> None:
    x = periapsis_state()
    got = kernel.rk4_step(models.two_body(MU), 0.4, x, dt)
    expected = textbook_rk4_step(two_body_numpy, 0.4, x, dt)
    np.testing.assert_allclose(got, expected, rtol=1e-14, atol=1e-15)


@pytest.mark.req("OGK-CORE-013")
def test_decay_matches_rk4_stability_polynomial() -> None:
    """For x' = -k x every RK4 step multiplies x by R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24,
    z = -k h: the discrete solution is known exactly (and close to exp(-k t))."""
    k, h, n = 1.7, 0.05, 60
    res = kernel.rk4_propagate(models.decay(k), [2.0], 0.0, n * h, h)
    z = -k * h
    growth = 1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24
    assert res.xf[0] == pytest.approx(2.0 * growth**n, rel=1e-13)
    assert res.xf[0] == pytest.approx(2.0 * np.exp(-k * n * h), rel=1e-5)


@pytest.mark.req("OGK-CORE-013")
def test_last_step_shortened_to_land_on_tf() -> None:
    k, h, tf = 0.9, 0.1, 0.35  # 3 full steps and one of 0.05
    res = kernel.rk4_propagate(models.decay(k), [1.0], 0.0, tf, h, dense_capacity=10)
    assert res.t_reached == tf and res.n_steps == 4
    assert res.dense is not None
    np.testing.assert_allclose(res.dense.t, [0.0, 0.1, 0.2, 0.3, 0.35], atol=1e-15)
    R = lambda z: 1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24  # noqa: E731
    assert res.xf[0] == pytest.approx(R(-k * h) ** 3 * R(-k * 0.05), rel=1e-14)


@pytest.mark.req("OGK-CORE-013")
def test_callback_failure_is_reported() -> None:
    with pytest.raises(kernel.KernelError) as info:
        kernel.rk4_propagate(models.decay(1.0, t_fail=0.5), [1.0], 0.0, 1.0, 0.1)
    assert info.value.code == lib.OGK_E_CALLBACK
    partial = info.value.partial
    assert isinstance(partial, kernel.Rk4Result)
    assert partial.t_reached <= 0.5 + 1e-12


@pytest.mark.req("OGK-CORE-013", "OGK-CORE-021")
def test_invalid_arguments() -> None:
    model = models.decay(1.0)
    for h in (0.0, -0.1, np.nan):
        with pytest.raises(kernel.KernelError) as info:
            kernel.rk4_propagate(model, [1.0], 0.0, 1.0, h)
        assert info.value.code == lib.OGK_E_RANGE
    with pytest.raises(kernel.KernelError) as info:
        kernel.rk4_propagate(model, [1.0], 0.0, 1.0, 0.1, dense_capacity=3)
    assert info.value.code == lib.OGK_E_DIM
    with pytest.raises(kernel.KernelError) as info:
        kernel.rk4_propagate(model, [np.nan], 0.0, 1.0, 0.1)
    assert info.value.code == lib.OGK_E_NONFINITE
    with pytest.raises(ValueError):
        kernel.rk4_propagate(model, [1.0, 2.0], 0.0, 1.0, 0.1)
