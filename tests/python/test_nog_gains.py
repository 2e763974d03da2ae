"""VTD-NOG gain tables of the LEO-to-GEO burn (host/ogk_host/orbit_injection/gains.py, docs/design/vtd-nog.md).

The main check is derivation-independent: from displaced states at tau_k = 0, 0.25, 0.5, 0.75 (with
position, velocity AND real-time offsets dt_k = t_k - t_f* tau_k), the full nonlinear remaining-arc
problem is re-solved (reference.py: shooting on the state/costate equations with the injection
conditions, h = -1, lambda_xi(1) = lambda_t(1) = 0), and the exact changes of the seven costates and of
t_f are compared with the gains' linear prediction. A correct first-order law leaves an error that
falls quadratically: x100 per decade of displacement. A wrong gain column (e.g. ignoring dt_k, which
is what a law without the time state does at tau_k > 0) would show a x10 ratio.
Also checked: the hand-derived partials against complex-step derivatives, the structure of the
accessory-problem matrices on the planar nominal, the conditioning of the 8x8 solve, the intra-
interval control hold against the exact linear neighboring extremal, and the SI table files.
Runtime: one nominal solve (~3-6 s) plus 12 re-solves (~3 s).
"""
from __future__ import annotations

import numpy as np
import pytest

from ogk_host import tablefile
from ogk_host.orbit_injection import dynamics as dyn
from ogk_host.orbit_injection import tables
from ogk_host.orbit_injection.gains import (GainTable, compute_gain_table, predict_control_correction,
                                    predict_correction, propagate_neighboring)
from ogk_host.orbit_injection.nominal import Nominal, solve_nominal
from ogk_host.orbit_injection.propagation import integrate_extremal
from ogk_host.orbit_injection.reference import solve_remaining_arc

TAU_CHECK = (0.0, 0.25, 0.5, 0.75)
SCALES = (1e-2, 1e-3, 1e-4)          # times a 1-sigma (Table 3) displacement plus a 1 s clock offset


@pytest.fixture(scope="module")
def nominal() -> Nominal:
    return solve_nominal()


@pytest.fixture(scope="module")
def table(nominal: Nominal) -> GainTable:
    return compute_gain_table(nominal)


@pytest.fixture(scope="module")
def check_table(nominal: Nominal) -> GainTable:
    """Gains exactly at the check points (no interpolation in the quadratic test)."""
    return compute_gain_table(nominal, np.array(TAU_CHECK))


def _displacement(nominal: Nominal, seed: int) -> np.ndarray:
    """Table 3 sigma with random signs, xi offset 1e-4 rad and dt_k = +-1 s (canonical units)."""
    scn = nominal.problem.scenario
    sigma_si = scn.initial_state_dispersion.sigma_state_si()
    sigma_si[dyn.XI] = 1e-4
    sigma_si[dyn.TIME] = 1.0
    signs = np.random.default_rng(seed).choice([-1.0, 1.0], size=dyn.N_X)
    return nominal.problem.units.state_from_si(signs * sigma_si)


@pytest.mark.req("OGK-NOG-014")
def test_partials_match_complex_step(nominal: Nominal) -> None:
    """f_x, f_u, h_x, h_xx, h_xu, h_uu (hand-derived) vs complex-step derivatives, 3-D states."""
    model = nominal.model
    rng = np.random.default_rng(7)
    step = 1e-30
    for _ in range(3):
        x = np.array([1.0, 0.3, 0.0, 0.01, 0.5, 0.0, 0.004]) + rng.normal(scale=[0.05, 0.1, 0.05,
                                                                                  0.01, 0.05, 0.01, 0.001])
        lam = rng.normal(size=dyn.N_X)
        u = rng.normal(scale=0.4, size=dyn.N_U)
        fx, fu = dyn.state_jacobians(model, x, u)
        h, h_x, h_u = dyn.costate_rate_terms(model, x, lam, u)
        hxx, hxu, huu = dyn.hamiltonian_hessians(model, x, lam, u)
        eye_x, eye_u = np.eye(dyn.N_X), np.eye(dyn.N_U)
        cs_fx = np.stack([dyn.state_rate(model, x + 1j * step * e, u).imag / step for e in eye_x], 1)
        cs_fu = np.stack([dyn.state_rate(model, x, u + 1j * step * e).imag / step for e in eye_u], 1)
        cs_hx = np.array([np.sum(lam * dyn.state_rate(model, x + 1j * step * e, u)).imag / step
                          for e in eye_x])
        cs_hxx = np.stack([dyn.costate_rate_terms(model, x + 1j * step * e, lam, u)[1].imag / step
                           for e in eye_x])
        cs_hxu = np.stack([dyn.costate_rate_terms(model, x, lam, u + 1j * step * e)[1].imag / step
                           for e in eye_u], 1)
        cs_huu = np.stack([dyn.costate_rate_terms(model, x, lam, u + 1j * step * e)[2].imag / step
                           for e in eye_u])
        for ours, ref in ((fx, cs_fx), (fu, cs_fu), (h_x, cs_hx), (hxx, cs_hxx), (hxu, cs_hxu),
                          (huu, cs_huu)):
            np.testing.assert_allclose(ours, ref, rtol=1e-12, atol=1e-12 * np.max(np.abs(ref)))
        assert h == pytest.approx(float(lam @ dyn.state_rate(model, x, u)), rel=1e-14)


@pytest.mark.req("OGK-NOG-014")
def test_accessory_matrices_on_planar_nominal(nominal: Nominal, table: GainTable) -> None:
    """On the nominal H_ux, H_ua, F vanish and H_uu = t_f a(t) |lambda_v| I (VTD-NOG-NOTES sec. 2)."""
    x, lam = table.z[:, :dyn.N_X], table.z[:, dyn.N_X:]
    mats = dyn.neighboring_matrices(nominal.model, x, lam, table.u, nominal.t_f)
    accel, _, _ = nominal.model.accel(x[:, dyn.TIME])
    expected = nominal.t_f * accel * np.hypot(lam[:, dyn.VR], lam[:, dyn.VT])
    np.testing.assert_allclose(mats.H_uu, expected[:, None, None] * np.eye(2)[None], rtol=1e-12,
                               atol=1e-15)
    assert np.max(np.abs(mats.K_x)) < 1e-12 and np.max(np.abs(mats.K_a)) < 1e-12
    assert np.max(np.abs(mats.F)) < 1e-14
    np.testing.assert_allclose(mats.D, dyn.state_rate(nominal.model, x, table.u), atol=1e-12)
    # t_f * h = t_f * lambda^T f~ = -t_f (parameter condition h = -1 holds all along the path)
    np.testing.assert_allclose(np.sum(lam * mats.D, axis=1), -1.0, atol=1e-11)


@pytest.mark.req("OGK-NOG-014")
def test_gain_solve_is_well_conditioned_after_equilibration(table: GainTable) -> None:
    """Raw cond(K_k) spans 6e5..4e10 over the default grid in canonical units (scaling only);
    equilibrated it stays ~10.2."""
    assert np.all(table.huu_min_eig > 0.0)
    assert table.cond_raw[0] > 1e5 and table.cond_raw[-1] > 1e10
    assert np.all(table.cond_equilibrated < 20.0)


@pytest.mark.req("OGK-NOG-014")
@pytest.mark.parametrize("tau_k", TAU_CHECK)
def test_gains_predict_exact_resolve_to_second_order(nominal: Nominal, check_table: GainTable,
                                                     tau_k: float) -> None:
    """Exact (re-solved) dlam_k, dt_f and du at the end of the sampling interval vs the linear
    prediction: errors fall x100 per decade (asserted in [30, 300] over two decades)."""
    k = TAU_CHECK.index(tau_k)
    gain = check_table.gain[k]
    z_nom = check_table.z[k]
    direction = _displacement(nominal, seed=100 + k)
    tau_next = tau_k + nominal.problem.scenario.sample_interval_s / nominal.t_f_s
    u_nom_next = dyn.optimal_control(nominal.states(np.array([tau_next]))[0, dyn.N_X:])
    errors, predictions = [], []
    for scale in SCALES:
        dx_k = scale * direction
        exact = solve_remaining_arc(nominal, tau_k, z_nom[:dyn.N_X] + dx_k)
        assert np.max(np.abs(exact.residuals)) < 1e-12
        predicted = gain @ dx_k
        exact_change = np.append(exact.lam_k - z_nom[dyn.N_X:], exact.t_f - nominal.t_f)
        # control at tau_k + Delta t_S / t_f*: exact extremal vs the linear neighboring extremal
        z_exact_next = integrate_extremal(nominal.model, np.append(exact.x_k, exact.lam_k), exact.t_f,
                                          tau_k, np.array([tau_next])).z[0]
        du_exact = dyn.optimal_control(z_exact_next[dyn.N_X:]) - u_nom_next
        correction = predict_correction(check_table, tau_k, dx_k)
        _, _, du_lin = propagate_neighboring(nominal, tau_k, dx_k, correction, np.array([tau_next]))
        errors.append(np.concatenate([np.abs(exact_change - predicted), np.abs(du_exact - du_lin[0])]))
        predictions.append(np.concatenate([np.abs(predicted), np.abs(du_lin[0])]))
    errors_arr, pred_arr = np.array(errors), np.array(predictions)
    active = pred_arr[-1] > 0.0                        # lambda_xi never responds (xi is ignorable)
    assert np.all(errors_arr[:, ~active] == 0.0)
    ratios = errors_arr[:-1, active] / errors_arr[1:, active]
    print(f"\ntau_k = {tau_k}: error ratio per decade, components "
          f"[dlam (r, phi, vr, vt, vn, t), dt_f, dalpha, dbeta]:\n{np.array2string(ratios, precision=1)}")
    assert np.all((ratios > 30.0) & (ratios < 300.0))
    # at the smallest displacement (1e-4 sigma) the linear law is within 1 % of each group's size
    for group in (slice(0, dyn.N_X), slice(dyn.N_X, dyn.N_X + 1), slice(dyn.N_X + 1, None)):
        assert np.max(errors_arr[-1, group]) < 1e-2 * np.max(pred_arr[-1, group])


@pytest.mark.req("OGK-NOG-014", "OGK-NOG-007")
def test_first_order_hold_serves_du_inside_interval(nominal: Nominal, table: GainTable) -> None:
    """du from the table's first-order costate hold vs the exact linear neighboring extremal over one
    sampling interval; the zero-order hold is shown to be much worse (both measured)."""
    dtau = nominal.problem.scenario.sample_interval_s / nominal.t_f_s
    for seed, tau_k in enumerate((0.0, 0.5, 0.9)):
        dx_k = 1e-2 * _displacement(nominal, seed=200 + seed)
        taus = tau_k + np.linspace(0.0, dtau, 9)
        corr = predict_correction(table, tau_k, dx_k)
        _, _, du_exact = propagate_neighboring(nominal, tau_k, dx_k, corr, taus)
        du_first = predict_control_correction(table, tau_k, dx_k, taus, "first-order")
        du_zero = predict_control_correction(table, tau_k, dx_k, taus, "zero-order")
        scale = np.max(np.abs(du_exact))
        err_first = np.max(np.abs(du_first - du_exact)) / scale
        err_zero = np.max(np.abs(du_zero - du_exact)) / scale
        print(f"\ntau_k = {tau_k}: relative du error, first-order hold {err_first:.2e}, "
              f"zero-order hold {err_zero:.2e}")
        assert err_first < 1e-4
        assert err_zero > 100.0 * err_first


@pytest.mark.req("OGK-NOG-014")
def test_table_interpolation_between_nodes(nominal: Nominal, table: GainTable) -> None:
    """Gains linearly interpolated at mid-nodes vs gains computed there: <1 % of the gain size."""
    mids = 0.5 * (table.tau[:-1] + table.tau[1:])
    exact = compute_gain_table(nominal, mids).gain
    interp = np.stack([predict_correction(table, t, np.eye(dyn.N_X)[j]).dlam_k
                       for t in mids for j in range(dyn.N_X)]).reshape(mids.size, dyn.N_X, dyn.N_X)
    rel = np.max(np.abs(np.swapaxes(interp, 1, 2) - exact[:, :dyn.N_X, :]), axis=(1, 2)) / np.max(
        np.abs(exact[:, :dyn.N_X, :]), axis=(1, 2))
    print(f"\nmax relative interpolation error of the costate gains: {rel.max():.2e}")
    assert np.all(rel < 1e-2)


@pytest.mark.req("OGK-NOG-014")
def test_table_files_round_trip_in_si(nominal: Nominal, table: GainTable, tmp_path) -> None:
    """The .ogkt files decode with the documented kinds/dims and reproduce the canonical gains in SI."""
    manifest = tables.write_nog_tables(tmp_path, nominal=nominal, table=table)
    assert len(manifest["files"]) == 7
    units = nominal.problem.units
    gain = tablefile.read_table(tmp_path / "gain.ogkt", tables.KIND_GAIN)
    assert gain.dims == (8, 7) and np.array_equal(gain.grid, table.tau)
    nom_tab = tablefile.read_table(tmp_path / "nominal.ogkt", tables.KIND_NOMINAL)
    assert nom_tab.dims == (4, 7)
    scalars = tablefile.read_table(tmp_path / "scalars.ogkt", tables.KIND_SCALARS)
    assert scalars.data[0, 0] == pytest.approx(nominal.t_f_s, rel=1e-15)
    # SI prediction = canonical prediction converted
    k = 37
    dx_si = units.state_to_si(_displacement(nominal, seed=5) * 1e-2)
    out_si = gain.data[k] @ dx_si
    out_can = table.gain[k] @ units.state_from_si(dx_si)
    np.testing.assert_allclose(out_si[:dyn.N_X], units.costate_to_si(out_can[:dyn.N_X]),
                               rtol=1e-12, atol=1e-12 * np.max(np.abs(out_si[:dyn.N_X])))
    assert out_si[dyn.N_X] == pytest.approx(out_can[dyn.N_X] * units.time_s, rel=1e-12)
    # nominal row 0 at tau = 0 is the SI ignition state; the time column is t_f* tau
    np.testing.assert_allclose(nom_tab.data[0, 0], units.state_to_si(nominal.z0[:dyn.N_X]),
                               rtol=1e-14)
    np.testing.assert_allclose(nom_tab.data[:, 0, dyn.TIME], nominal.t_f_s * table.tau,
                               rtol=1e-10, atol=1e-9)


@pytest.mark.req("OGK-NOG-014")
def test_check_detects_a_first_order_gain_error(nominal: Nominal, check_table: GainTable) -> None:
    """Negative control: dropping the real-time column of the gains (treating t_k as t_f* tau_k)
    leaves a first-order error at tau_k = 0.5, and the same check then measures ~x10 per decade."""
    k = TAU_CHECK.index(0.5)
    gain = check_table.gain[k].copy()
    gain[:, dyn.TIME] = 0.0
    z_nom = check_table.z[k]
    direction = _displacement(nominal, seed=100 + k)
    errors = []
    for scale in SCALES[1:]:
        dx_k = scale * direction
        exact = solve_remaining_arc(nominal, 0.5, z_nom[:dyn.N_X] + dx_k)
        errors.append(abs(exact.t_f - nominal.t_f - float(gain[dyn.N_X] @ dx_k)))
    ratio = errors[0] / errors[1]
    print(f"\nwithout the dt_k column: dt_f error ratio per decade {ratio:.1f}")
    assert 5.0 < ratio < 20.0


@pytest.mark.req("OGK-NOG-014")
def test_flight_bundle_matches_nog_h_layout(nominal: Nominal, table: GainTable, tmp_path) -> None:
    """nog_bundle.ogkt: kind/length/grid of kernel/include/ogk/nog.h, blocks equal to the
    separate tables, tau = 1 node with zero gains, x*' of the time state = t_f* everywhere."""
    tables.write_nog_tables(tmp_path, nominal=nominal, table=table)
    bundle = tablefile.read_table(tmp_path / "nog_bundle.ogkt", tables.KIND_NOG_BUNDLE)
    assert tables.KIND_NOG_BUNDLE == 0x4E4F4742 and bundle.dims == (133,)
    assert bundle.grid[0] == 0.0 and bundle.grid[-1] == 1.0 and np.all(np.diff(bundle.grid) > 0.0)
    assert bundle.grid.size <= tables.kernel_table_capacity()[0]
    n = table.tau.size
    nom_tab = tablefile.read_table(tmp_path / "nominal.ogkt").data.reshape(n, -1)
    gain = tablefile.read_table(tmp_path / "gain.ogkt").data.reshape(n, -1)
    rate = tablefile.read_table(tmp_path / "costate_rate_gain.ogkt").data.reshape(n, -1)
    np.testing.assert_array_equal(bundle.data[:n, 0:28], nom_tab)
    np.testing.assert_array_equal(bundle.data[:n, 28:84], gain)
    np.testing.assert_array_equal(bundle.data[:n, 84:133], rate)
    assert np.all(bundle.data[-1, 28:] == 0.0)
    np.testing.assert_allclose(bundle.data[:, 7 + dyn.TIME], nominal.t_f_s, rtol=1e-14)
    units = nominal.problem.units
    z1 = nominal.states(np.array([1.0]))[0]
    np.testing.assert_allclose(bundle.data[-1, 0:7], units.state_to_si(z1[:dyn.N_X]), rtol=1e-14)
    # h = -1 in SI too: lambda*^T x*' / t_f* = -1 at every node
    np.testing.assert_allclose(np.sum(bundle.data[:, 14:21] * bundle.data[:, 7:14], axis=1)
                               / nominal.t_f_s, -1.0, atol=1e-10)
