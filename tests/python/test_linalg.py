"""Kernel dense linear algebra vs numpy.linalg (spot checks; the Eigen program
tests/eigen is the main cross-check)."""
from __future__ import annotations

import numpy as np
import pytest

from ogk_bindings import kernel
from ogk_bindings._ffi import lib


def well_conditioned(rng: np.random.Generator, n: int) -> np.ndarray:
    return rng.standard_normal((n, n)) + n * np.eye(n)


@pytest.mark.req("OGK-CORE-011")
@pytest.mark.parametrize("n", [1, 2, 5, 16])
def test_lu_solve_and_inverse(rng: np.random.Generator, n: int) -> None:
    A = rng.standard_normal((n, n)) + 0.5 * np.eye(n)
    b = rng.standard_normal(n)
    B = rng.standard_normal((n, 3))
    cond = np.linalg.cond(A)
    tol = 1e-14 * cond * 10
    np.testing.assert_allclose(kernel.lu_solve(A, b), np.linalg.solve(A, b), rtol=tol, atol=tol)
    np.testing.assert_allclose(kernel.lu_solve(A, B), np.linalg.solve(A, B), rtol=tol, atol=tol)
    np.testing.assert_allclose(kernel.lu_inverse(A), np.linalg.inv(A), rtol=tol, atol=tol)


@pytest.mark.req("OGK-CORE-011")
@pytest.mark.parametrize("n", [2, 6, 16])
def test_lu_rcond_is_exact_1norm(rng: np.random.Generator, n: int) -> None:
    A = rng.standard_normal((n, n))
    expected = 1.0 / (np.linalg.norm(A, 1) * np.linalg.norm(np.linalg.inv(A), 1))
    lu = kernel.lu_factor(A)
    assert lu.rcond == pytest.approx(expected, rel=1e-9)
    assert lu.anorm1 == pytest.approx(np.linalg.norm(A, 1), rel=1e-15)


@pytest.mark.req("OGK-CORE-011")
def test_lu_singular_and_ill_conditioned() -> None:
    with pytest.raises(kernel.KernelError) as info:
        kernel.lu_solve(np.array([[1.0, 2.0], [2.0, 4.0]]), [1.0, 1.0])
    assert info.value.code == lib.OGK_E_SINGULAR
    hilbert = 1.0 / (np.arange(12)[:, None] + np.arange(12)[None, :] + 1.0)
    with pytest.raises(kernel.KernelError) as info:
        kernel.lu_solve(hilbert, np.ones(12))
    assert info.value.code == lib.OGK_E_ILL_CONDITIONED
    rcond = kernel.lu_rcond(hilbert)  # factors are kept; rcond still reported
    assert 0.0 < rcond < float(lib.OGK_LA_RCOND_MIN)
    expected = 1.0 / (np.linalg.norm(hilbert, 1) * np.linalg.norm(np.linalg.inv(hilbert), 1))
    assert rcond == pytest.approx(expected, rel=0.5)


@pytest.mark.req("OGK-CORE-011", "OGK-CORE-005")
def test_lu_dimension_limit(rng: np.random.Generator) -> None:
    n = int(lib.OGK_LA_MAX_N) + 1
    with pytest.raises(kernel.KernelError) as info:
        kernel.lu_solve(well_conditioned(rng, n), np.ones(n))
    assert info.value.code == lib.OGK_E_DIM


@pytest.mark.req("OGK-CORE-011")
@pytest.mark.parametrize("n", [1, 4, 16])
def test_cholesky_solve(rng: np.random.Generator, n: int) -> None:
    M = rng.standard_normal((n, n))
    A = M @ M.T + n * np.eye(n)
    b = rng.standard_normal(n)
    np.testing.assert_allclose(kernel.cholesky_solve(A, b), np.linalg.solve(A, b),
                               rtol=1e-12, atol=1e-13)


@pytest.mark.req("OGK-CORE-011")
def test_cholesky_rejects_indefinite_and_unsymmetric() -> None:
    for A in (np.array([[1.0, 2.0], [2.0, 1.0]]), np.array([[2.0, 1.0], [0.0, 2.0]])):
        with pytest.raises(kernel.KernelError) as info:
            kernel.cholesky_solve(A, [1.0, 1.0])
        assert info.value.code == lib.OGK_E_NOT_POSDEF


@pytest.mark.req("OGK-CORE-012")
@pytest.mark.parametrize("m, n", [(3, 3), (20, 5), (128, 16)])
def test_lstsq_vs_numpy(rng: np.random.Generator, m: int, n: int) -> None:
    A = rng.standard_normal((m, n))
    b = rng.standard_normal(m)
    expected = np.linalg.lstsq(A, b, rcond=None)[0]
    np.testing.assert_allclose(kernel.lstsq(A, b), expected, rtol=1e-11, atol=1e-12)


@pytest.mark.req("OGK-CORE-012")
@pytest.mark.parametrize("m, n", [(3, 3), (5, 20), (16, 128)])
def test_minnorm_vs_numpy(rng: np.random.Generator, m: int, n: int) -> None:
    A = rng.standard_normal((m, n))
    b = rng.standard_normal(m)
    x = kernel.minnorm(A, b)
    np.testing.assert_allclose(x, np.linalg.pinv(A) @ b, rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(A @ x, b, atol=1e-12)


@pytest.mark.req("OGK-CORE-012")
def test_lstsq_rank_deficient() -> None:
    A = np.ones((6, 2))
    with pytest.raises(kernel.KernelError) as info:
        kernel.lstsq(A, np.ones(6))
    assert info.value.code in (lib.OGK_E_SINGULAR, lib.OGK_E_ILL_CONDITIONED)


@pytest.mark.req("OGK-CORE-010")
def test_products_vs_numpy(rng: np.random.Generator) -> None:
    A = rng.standard_normal((7, 4))
    B = rng.standard_normal((4, 9))
    x = rng.standard_normal(4)
    np.testing.assert_allclose(kernel.mat_vec(A, x), A @ x, rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(kernel.mat_mul(A, B), A @ B, rtol=1e-14, atol=1e-14)


@pytest.mark.req("OGK-HAR-010")
def test_wrapper_checks_vector_lengths(rng: np.random.Generator) -> None:
    """The C functions cannot see buffer sizes; the wrappers must refuse short vectors."""
    A = well_conditioned(rng, 4)
    for call in (lambda: kernel.mat_vec(A, np.ones(3)),
                 lambda: kernel.lu_solve(A, np.ones(5)),
                 lambda: kernel.cholesky_solve(A @ A.T, np.ones(3)),
                 lambda: kernel.lstsq(rng.standard_normal((6, 3)), np.ones(5)),
                 lambda: kernel.minnorm(rng.standard_normal((3, 6)), np.ones(6))):
        with pytest.raises(ValueError):
            call()
