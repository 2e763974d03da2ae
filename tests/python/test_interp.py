"""Kernel interpolation vs numpy.interp (linear) and scipy PchipInterpolator (pchip)."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from ogk_bindings import kernel
from ogk_bindings._ffi import lib

pytestmark = pytest.mark.req("OGK-CORE-015")


def random_grid(rng: np.random.Generator, n: int) -> np.ndarray:
    """Non-uniform strictly increasing grid on [0, 1] (spacing ratios up to ~20)."""
    steps = rng.uniform(0.05, 1.0, n - 1)
    return np.concatenate([[0.0], np.cumsum(steps) / steps.sum()])


def queries(rng: np.random.Generator, grid: np.ndarray) -> np.ndarray:
    """Random points, the nodes themselves and both ends."""
    return np.concatenate([rng.uniform(grid[0], grid[-1], 200), grid])


@pytest.mark.parametrize("n", [2, 3, 7, 40])
def test_linear_vs_numpy(rng: np.random.Generator, n: int) -> None:
    grid = random_grid(rng, n)
    values = rng.standard_normal((n, 3))
    tau = queries(rng, grid)
    got = kernel.interp_linear(grid, values, tau)
    assert got.shape == (tau.size, 3)
    for j in range(3):
        np.testing.assert_allclose(got[:, j], np.interp(tau, grid, values[:, j]),
                                   rtol=0, atol=1e-14)


@pytest.mark.parametrize("n", [2, 3, 4, 9, 50])
@pytest.mark.parametrize("data", ["smooth", "steps"])
def test_pchip_vs_scipy(rng: np.random.Generator, n: int, data: str) -> None:
    grid = random_grid(rng, n)
    if data == "smooth":
        values = rng.standard_normal((n, 4))
    else:
        # Small integers: flat runs, local extrema and sign changes of the secants
        # exercise every branch of the Fritsch-Carlson slope rule.
        values = rng.integers(-2, 3, (n, 4)).astype(float)
    tau = queries(rng, grid)
    reference = PchipInterpolator(grid, values, axis=0)
    slopes = kernel.pchip_slopes(grid, values)
    np.testing.assert_allclose(slopes, reference.derivative()(grid), rtol=1e-12, atol=1e-12)
    got = kernel.interp_pchip(grid, values, tau, slopes)
    np.testing.assert_allclose(got, reference(tau), rtol=1e-12, atol=1e-13)


def test_pchip_is_monotone_on_monotone_data(rng: np.random.Generator) -> None:
    grid = random_grid(rng, 15)
    values = np.cumsum(rng.exponential(1.0, 15) * (rng.uniform(size=15) > 0.3))
    fine = np.linspace(0.0, 1.0, 2001)
    got = kernel.interp_pchip(grid, values, fine)
    assert np.all(np.diff(got) >= -1e-14)


def test_scalar_values_shape() -> None:
    grid = np.array([0.0, 0.5, 1.0])
    out = kernel.interp_linear(grid, np.array([1.0, 3.0, 2.0]), 0.25)
    assert out.shape == () and float(out) == pytest.approx(2.0, abs=1e-15)


@pytest.mark.parametrize("tau", [-1e-12, 1.0 + 1e-12, -5.0, 7.0])
def test_out_of_range_tau(rng: np.random.Generator, tau: float) -> None:
    grid = random_grid(rng, 6)
    values = rng.standard_normal((6, 2))
    for call in (lambda: kernel.interp_linear(grid, values, tau),
                 lambda: kernel.interp_pchip(grid, values, tau),
                 lambda: kernel.interp_locate(grid, tau)):
        with pytest.raises(kernel.KernelError) as info:
            call()
        assert info.value.code == lib.OGK_E_RANGE


def test_locate_vs_searchsorted(rng: np.random.Generator) -> None:
    grid = random_grid(rng, 30)
    for tau in queries(rng, grid):
        k = kernel.interp_locate(grid, tau)
        expected = min(int(np.searchsorted(grid, tau, side="right")) - 1, grid.size - 2)
        assert k == expected


@pytest.mark.parametrize("grid, code", [
    ([0.0], lib.OGK_E_DIM),
    ([0.0, 0.0, 1.0], lib.OGK_E_RANGE),
    ([0.0, 2.0, 1.0], lib.OGK_E_RANGE),
    ([0.0, np.nan, 1.0], lib.OGK_E_NONFINITE),
    ([0.0, 0.5, np.inf], lib.OGK_E_NONFINITE),
])
def test_check_grid_rejects(grid: list[float], code: int) -> None:
    with pytest.raises(kernel.KernelError) as info:
        kernel.interp_check_grid(grid)
    assert info.value.code == code


def test_check_grid_accepts() -> None:
    kernel.interp_check_grid([0.0, 1e-9, 0.5, 1.0])
