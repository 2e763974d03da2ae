"""CPD attitude control: gain design (host/ogk_host/cpd_design.py) and the kernel bindings
(bindings/ogk_bindings/cpd.py) against independent references.

References: numpy.roots for the closed-loop poles; the paper's printed numbers (eq. 54 and the text
after it, sec. 7); scipy.spatial.transform.Rotation for the Euler sequence of eq. (9) and for the
shortest-arc rotation (body pointing error); scipy.integrate.solve_ivp for the sampled loop.
"""
from __future__ import annotations

import dataclasses

import math
import tomllib

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from ogk_bindings import cpd
from ogk_bindings.kernel import KernelError, Status
from ogk_host import cpd_design as cd

DEG = math.pi / 180.0
TAU = 0.1
DELTA_C_MAX = 0.65 * DEG
M_XC_MAX = 30.0


# ----------------------------------------------------------------- gain design
@pytest.mark.req("OGK-CPD-011")
def test_printed_gains_follow_from_printed_g() -> None:
    """Sec. 5.3 on eq. (54)'s printed G reproduces the printed gains to their 3 digits."""
    design = cd.printed_design().as_config_dict()
    for name, printed in cd.PRINTED_GAINS.items():
        assert design[name] == pytest.approx(printed, rel=4e-3), name
    # 0.83 is T l0 / I_y0 with T in kgf (n0 = 1.112 "g" without g0): that value rounds exactly
    g_kgf = 1.112 * 2400.0 * 0.25 / 800.0
    axis = cd.design_axis(g_kgf, cd.PAPER_OMEGA_N_RAD_S, cd.PAPER_ZETA)
    assert round(g_kgf, 2) == 0.83
    assert round(axis.k_p, 1) == 21.6
    assert axis.k_d == pytest.approx(7.20, abs=0.012)       # 7.19


@pytest.mark.req("OGK-CPD-011")
def test_scout_pitch_gains_from_printed_g() -> None:
    """Sec. 7: omega_n = 4.24, zeta = 1 on G_y = 361.05 s^-2 gives k_py = 0.050, k_dy = 0.023."""
    axis = cd.design_axis(361.05, 4.24, 1.0)
    assert round(axis.k_p, 3) == 0.050
    assert round(axis.k_d, 3) == 0.023


@pytest.mark.req("OGK-CPD-011")
def test_true_effectiveness_is_about_8_2() -> None:
    """Erratum on eq. (54): G_y = T l0 / I_y0 with T = n0 m0 is ~8.18 s^-2, not 0.83."""
    vehicle = cd.leo_geo_vehicle()
    thrust = 1.112 * 9.80665 * 2400.0
    g = vehicle.effectiveness(0.0)
    assert g[1] == pytest.approx(thrust * 0.25 / 800.0, rel=1e-14)
    assert g[1] == pytest.approx(8.18, abs=0.005)
    assert g[0] == pytest.approx(1.0 / 1200.0, rel=1e-14)
    # eq. (53) at the end of the burn: l grows, I_y shrinks -> G_y max at t_b
    tb = vehicle.burn_time_s
    g_min, g_max = cd.effectiveness_range(vehicle)
    assert g_max[1] == pytest.approx(thrust * (0.25 + 2.4e-3 * tb) / (800.0 - 2.91 * tb), rel=1e-12)
    assert g_max[0] == pytest.approx(1.0 / (1200.0 - 4.36 * tb), rel=1e-12)
    assert g_min[1] == pytest.approx(g[1], rel=1e-14)
    gains = cd.design_gains(vehicle)
    assert gains.pitch.k_p == pytest.approx(4.24**2 / g[1], rel=1e-14)
    assert gains.pitch.k_d == pytest.approx(2 * 0.707 * 4.24 / g[1], rel=1e-14)
    assert gains.yaw == gains.pitch


@pytest.mark.req("OGK-CPD-011")
def test_scenario_file_agrees_with_design() -> None:
    """scenarios/leo_geo.toml's [cpd.rederived] gains are what this tool designs from its data."""
    with open(cd.LEO_GEO_SCENARIO, "rb") as fh:
        stored = tomllib.load(fh)["cpd"]["rederived"]
    gains = cd.design_gains(cd.vehicle_from_scenario())
    assert gains.roll.k_p == pytest.approx(stored["kp_roll_n_m_per_rad"], rel=1e-6)
    assert gains.roll.k_d == pytest.approx(stored["kd_roll_n_m_s_per_rad"], rel=1e-6)
    assert gains.pitch.k_p == pytest.approx(stored["kp_pitch_yaw"], rel=1e-6)
    assert gains.pitch.k_d == pytest.approx(stored["kd_pitch_yaw_s"], rel=1e-6)


def _omega_zeta_from_roots(g: float, k_p: float, k_d: float) -> tuple[float, float]:
    p1, p2 = np.roots([1.0, g * k_d, g * k_p])
    omega_n = math.sqrt((p1 * p2).real)          # also right for real (overdamped) poles
    zeta = -(p1 + p2).real / (2.0 * omega_n)
    assert p1.real < 0 and p2.real < 0
    return omega_n, zeta


@pytest.mark.req("OGK-CPD-011")
@pytest.mark.parametrize("omega_n,zeta", [(4.24, 0.707), (2.0, 0.5), (6.0, 1.0)])
def test_designed_poles_meet_specs_over_the_burn(omega_n: float, zeta: float) -> None:
    """zeta >= zeta_min and omega_n >= omega_min for all G in [G_min, G_max] (eq. 48 poles),
    with equality at G_min."""
    gains = cd.design_gains(cd.leo_geo_vehicle(), omega_n, zeta)
    for axis in (gains.roll, gains.pitch, gains.yaw):
        for g in np.linspace(axis.g_min, axis.g_max, 200):
            w, z = _omega_zeta_from_roots(g, axis.k_p, axis.k_d)
            assert w >= omega_n * (1 - 1e-12)
            assert z >= zeta * (1 - 1e-12)
        w, z = _omega_zeta_from_roots(axis.g_min, axis.k_p, axis.k_d)
        assert w == pytest.approx(omega_n, rel=1e-10)
        assert z == pytest.approx(zeta, rel=1e-10)
        # the analytic helpers say the same
        assert axis.omega_n(axis.g_max) == pytest.approx(
            _omega_zeta_from_roots(axis.g_max, axis.k_p, axis.k_d)[0], rel=1e-10)
        assert axis.zeta(axis.g_max) == pytest.approx(
            _omega_zeta_from_roots(axis.g_max, axis.k_p, axis.k_d)[1], rel=1e-10)


@pytest.mark.req("OGK-CPD-011")
def test_printed_gains_on_true_g_are_far_faster_than_designed() -> None:
    """Printed pitch gains on the true G: omega_n 13..24 rad/s, zeta 2.2..4.0 (not 4.24, 0.707)."""
    g_min, g_max = cd.effectiveness_range(cd.leo_geo_vehicle())
    pitch = cd.printed_gains().pitch
    w0, z0 = _omega_zeta_from_roots(g_min[1], pitch.k_p, pitch.k_d)
    w1, z1 = _omega_zeta_from_roots(g_max[1], pitch.k_p, pitch.k_d)
    assert (round(w0, 1), round(w1, 1)) == (13.3, 24.1)
    assert (round(z0, 1), round(z1, 1)) == (2.2, 4.0)


@pytest.mark.req("OGK-CPD-011", "OGK-CPD-006")
def test_actuator_loop_stability_is_the_papers_condition(rng: np.random.Generator) -> None:
    """tau s^3 + s^2 + G k_d s + G k_p is Hurwitz iff k_d > k_p tau (sec. 5.2)."""
    for _ in range(200):
        g, k_p, tau = rng.uniform(0.1, 50.0), rng.uniform(0.1, 50.0), rng.uniform(0.01, 0.5)
        for factor, stable in ((1.01, True), (0.99, False)):
            poles = cd.actuator_loop_poles(g, k_p, factor * k_p * tau, tau)
            assert (np.max(poles.real) < 0) == stable


@pytest.mark.req("OGK-CPD-011")
def test_phase_margin_definition() -> None:
    """|L(j w_c)| = 1 and PM = 180 + arg L(j w_c), evaluated here from the transfer function."""
    for g, k_p, k_d in ((8.18, 21.6, 7.2), (26.8, 2.198, 0.733), (1 / 1200, 21573.0, 7194.0)):
        wc, pm = cd.phase_margin(g, k_p, k_d, TAU)
        s = 1j * wc
        loop = g * (k_p + k_d * s) / (s * s * (TAU * s + 1))
        assert abs(loop) == pytest.approx(1.0, rel=1e-9)
        assert pm == pytest.approx(180.0 + math.degrees(math.atan2(loop.imag, loop.real)), abs=1e-9)
    # the figures quoted in docs/design/cpd.md
    g_min, g_max = cd.effectiveness_range(cd.leo_geo_vehicle())
    pm_printed = cd.phase_margin(float(g_max[1]), 21.6, 7.2, TAU)[1]
    pm_rederived = cd.phase_margin(float(g_max[1]), 2.198, 0.7330, TAU)[1]
    assert 8.0 < pm_printed < 10.0
    assert 24.0 < pm_rederived < 26.0


def _simulate_sampled_pitch(g: float, gains: cd.AxisGains, period: float, n: int,
                            err0: float) -> tuple[np.ndarray, int]:
    """Pitch axis of eqs. (42)-(44) with the KERNEL computing delta_yc every `period` (held),
    integrated by solve_ivp between samples; returns |pitch error| at each sample and the
    number of saturated commands."""
    cfg = cpd.CpdConfig(k_px=21573.0, k_dx=7194.0, k_py=gains.k_p, k_dy=gains.k_d,
                        k_pz=gains.k_p, k_dz=gains.k_d, m_xc_max=M_XC_MAX,
                        delta_yc_max=DELTA_C_MAX, delta_zc_max=DELTA_C_MAX,
                        tau_x=TAU, tau_y=TAU, tau_z=TAU)
    ctl = cpd.Cpd(cfg)
    theta_c = 0.3
    x = np.array([theta_c + err0, 0.0, 0.0])     # theta, Q, delta_y
    errors = np.empty(n)
    n_sat = 0
    for k in range(n):
        errors[k] = abs(x[0] - theta_c)
        out = ctl.step(cpd.CpdInput(theta=x[0], rate_q=x[1], alpha_c=theta_c))
        u = out.delta_yc
        n_sat += bool(out.flags & cpd.Flag.SAT_Y)

        def rhs(_t: float, y: np.ndarray, u: float = u) -> list[float]:
            return [y[1], g * y[2], (u - y[2]) / TAU]

        x = solve_ivp(rhs, (0.0, period), x, rtol=1e-10, atol=1e-14, method="DOP853").y[:, -1]
    return errors, n_sat


@pytest.mark.req("OGK-CPD-011", "OGK-CPD-012")
def test_max_stable_period_matches_kernel_in_the_loop() -> None:
    """The printed gains at the end of the burn (G = 26.8 s^-2): stable just below the predicted
    longest control period, unstable just above it, with the kernel computing the command."""
    g = float(cd.effectiveness_range(cd.leo_geo_vehicle())[1][1])
    gains = cd.printed_gains().pitch
    t_max = cd.max_stable_period(g, gains.k_p, gains.k_d, TAU)
    assert 6e-3 < t_max < 9e-3
    err0 = 1e-3 * DEG                              # well inside the 0.03 deg linear band
    stable, n_sat_stable = _simulate_sampled_pitch(g, gains, 0.7 * t_max, 600, err0)
    unstable, n_sat_unstable = _simulate_sampled_pitch(g, gains, 1.3 * t_max, 600, err0)
    assert stable[-100:].max() < 0.01 * err0 and n_sat_stable == 0
    # unstable: the fast mode grows until the rate term saturates the command (0.09 deg/s band),
    # then CPD's saturation holds it in a limit cycle: the TVC chatters at +-0.65 deg
    assert unstable[300:].max() > 2.5 * unstable[100:200].max()
    assert n_sat_unstable > 50
    # and the same check on the eigenvalues of the sampled loop
    assert cd.sampled_spectral_radius(g, gains.k_p, gains.k_d, TAU, 0.95 * t_max) < 1.0
    assert cd.sampled_spectral_radius(g, gains.k_p, gains.k_d, TAU, 1.05 * t_max) > 1.0


@pytest.mark.req("OGK-CPD-011")
def test_report_runs() -> None:
    text = cd.report(n_g=3)
    assert "RE-DERIVED" in text and "PRINTED" in text


# ----------------------------------------------------------------- kernel vs numpy
R_A = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])  # rows: a1, a2, a3 in c


def _rtn(xi: float, phi: float) -> np.ndarray:
    """Rows r, t, n in c components."""
    r = np.array([math.cos(phi) * math.cos(xi), math.cos(phi) * math.sin(xi), math.sin(phi)])
    t = np.array([-math.sin(xi), math.cos(xi), 0.0])
    return np.array([r, t, np.cross(r, t)])


def _body_axes_c(psi: float, theta: float, phi_roll: float) -> np.ndarray:
    """Columns x_b, y_b, z_b in c components: intrinsic z-y-x turns of the a axes (eq. 9)."""
    turn = Rotation.from_euler("ZYX", [psi, theta, phi_roll]).as_matrix()  # columns in a
    return R_A.T @ turn


def _direction(alpha: float, beta: float, xi: float, phi: float) -> np.ndarray:
    u = np.array([math.cos(beta) * math.sin(alpha), math.cos(beta) * math.cos(alpha),
                  math.sin(beta)])
    return _rtn(xi, phi).T @ u


def _ref_commanded_attitude(alpha: float, beta: float, xi: float,
                            phi: float) -> tuple[float, float]:
    t_a = R_A @ _direction(alpha, beta, xi, phi)           # eq. (38): (cTh cPs, cTh sPs, -sTh)
    return math.atan2(t_a[1], t_a[0]), math.asin(-t_a[2])


def _ref_thrust_angles(psi: float, theta: float, roll: float, xi: float, phi: float,
                       dy: float, dz: float) -> tuple[float, float]:
    b = _body_axes_c(psi, theta, roll)
    d = b @ np.array([math.cos(dz) * math.cos(dy), math.sin(dz), math.cos(dz) * math.sin(dy)])
    r, t, n = _rtn(xi, phi) @ d
    return math.atan2(r, t), math.asin(n)


def _random_case(rng: np.random.Generator) -> dict[str, float]:
    return {"psi": rng.uniform(-np.pi, np.pi), "theta": rng.uniform(-1.4, 1.4),
            "phi_roll": rng.uniform(-np.pi, np.pi), "alpha_c": rng.uniform(-np.pi, np.pi),
            "beta_c": rng.uniform(-1.4, 1.4), "xi": rng.uniform(-np.pi, np.pi),
            "phi": rng.uniform(-1.4, 1.4)}


@pytest.mark.req("OGK-CPD-002")
def test_commanded_attitude_matches_numpy(rng: np.random.Generator) -> None:
    alpha, beta = rng.uniform(-np.pi, np.pi, 300), rng.uniform(-1.5, 1.5, 300)
    xi, phi = rng.uniform(-np.pi, np.pi, 300), rng.uniform(-1.5, 1.5, 300)
    psi_c, theta_c = cpd.commanded_attitude(alpha, beta, xi, phi)
    ref = np.array([_ref_commanded_attitude(*args) for args in zip(alpha, beta, xi, phi)])
    np.testing.assert_allclose(psi_c, ref[:, 0], atol=1e-12)
    np.testing.assert_allclose(theta_c, ref[:, 1], atol=1e-12)
    # x_b of the commanded attitude is the commanded direction (any roll)
    for k in range(20):
        x_b = _body_axes_c(psi_c[k], theta_c[k], rng.uniform(-np.pi, np.pi))[:, 0]
        np.testing.assert_allclose(x_b, _direction(alpha[k], beta[k], xi[k], phi[k]), atol=1e-13)


@pytest.mark.req("OGK-CPD-003")
def test_thrust_angles_match_numpy(rng: np.random.Generator) -> None:
    for _ in range(300):
        c = _random_case(rng)
        dy, dz = rng.uniform(-0.2, 0.2, 2)
        got = cpd.thrust_angles(c["psi"], c["theta"], c["phi_roll"], c["xi"], c["phi"], dy, dz)
        ref = _ref_thrust_angles(c["psi"], c["theta"], c["phi_roll"], c["xi"], c["phi"], dy, dz)
        assert got[0] == pytest.approx(ref[0], abs=1e-12)
        assert got[1] == pytest.approx(ref[1], abs=1e-12)


def _ref_body_error(c: dict[str, float]) -> np.ndarray:
    """Shortest-arc rotation x_b -> T_c (scipy align_vectors), in body components."""
    b = _body_axes_c(c["psi"], c["theta"], c["phi_roll"])
    t_body = b.T @ _direction(c["alpha_c"], c["beta_c"], c["xi"], c["phi"])
    rot, _ = Rotation.align_vectors([t_body], [[1.0, 0.0, 0.0]])
    return rot.as_rotvec()


def _ref_step(c: dict[str, float], rates: np.ndarray, cfg: cpd.CpdConfig) -> dict[str, float]:
    """Eqs. (45)-(46) with the pointing error of cfg.pointing."""
    psi_c, theta_c = _ref_commanded_attitude(c["alpha_c"], c["beta_c"], c["xi"], c["phi"])
    wrap = lambda a: math.pi - (math.pi - a) % (2 * math.pi)  # noqa: E731  (-pi, pi]
    e_x = wrap(cfg.phi_c - c["phi_roll"])
    if cfg.pointing == cpd.Pointing.BODY:
        _, e_y, e_z = _ref_body_error(c)
    else:
        e_y, e_z = theta_c - c["theta"], wrap(psi_c - c["psi"])
    return {
        "m_xc": float(np.clip(cfg.k_px * e_x - cfg.k_dx * rates[0], -cfg.m_xc_max, cfg.m_xc_max)),
        "delta_yc": float(np.clip(cfg.k_py * e_y - cfg.k_dy * rates[1], -cfg.delta_yc_max,
                                  cfg.delta_yc_max)),
        "delta_zc": float(np.clip(-cfg.k_pz * e_z + cfg.k_dz * rates[2], -cfg.delta_zc_max,
                                  cfg.delta_zc_max)),
        "err_x": e_x, "err_y": e_y, "err_z": e_z, "psi_c": psi_c, "theta_c": theta_c,
    }


def _config(pointing: cpd.Pointing, gains: cd.CpdGains | None = None) -> cpd.CpdConfig:
    gains = gains or cd.design_gains(cd.leo_geo_vehicle())
    return cpd.CpdConfig(**gains.as_config_dict(), m_xc_max=M_XC_MAX, delta_yc_max=DELTA_C_MAX,
                         delta_zc_max=DELTA_C_MAX, tau_x=TAU, tau_y=TAU, tau_z=TAU,
                         phi_c=0.1, pointing=pointing)


@pytest.mark.req("OGK-CPD-001")
@pytest.mark.parametrize("pointing", [cpd.Pointing.BODY, cpd.Pointing.EULER])
def test_step_matches_numpy(pointing: cpd.Pointing, rng: np.random.Generator) -> None:
    """Random attitudes (large errors, saturated) and near-commanded ones (linear)."""
    cfg = _config(pointing)
    ctl = cpd.Cpd(cfg)
    n_linear = 0
    for k in range(400):
        c = _random_case(rng)
        if k % 2:  # near the commanded attitude: linear region
            psi_c, theta_c = _ref_commanded_attitude(c["alpha_c"], c["beta_c"], c["xi"], c["phi"])
            c["psi"], c["theta"] = psi_c + rng.normal(0, 1e-4), theta_c + rng.normal(0, 1e-4)
            c["phi_roll"] = cfg.phi_c + rng.normal(0, 1e-5)
            rates = rng.normal(0, 1e-4, 3)
        else:
            rates = rng.normal(0, 0.2, 3)
        out = ctl.step(cpd.CpdInput(**c, rate_p=rates[0], rate_q=rates[1], rate_r=rates[2]))
        ref = _ref_step(c, rates, cfg)
        for name in ("err_x", "err_y", "err_z", "psi_c", "theta_c"):
            assert getattr(out, name) == pytest.approx(ref[name], abs=1e-10), name
        assert out.m_xc == pytest.approx(ref["m_xc"], abs=1e-6)
        assert out.delta_yc == pytest.approx(ref["delta_yc"], abs=1e-12)
        assert out.delta_zc == pytest.approx(ref["delta_zc"], abs=1e-12)
        assert bool(out.flags & cpd.Flag.SAT_Y) == (abs(ref["delta_yc"]) == cfg.delta_yc_max)
        n_linear += not (out.flags & (cpd.Flag.SAT_X | cpd.Flag.SAT_Y | cpd.Flag.SAT_Z))
    assert n_linear > 100          # both regimes were exercised


@pytest.mark.req("OGK-CPD-004")
def test_body_error_is_roll_independent(rng: np.random.Generator) -> None:
    for _ in range(50):
        c = _random_case(rng)
        mags = []
        for roll in np.radians([0.0, 45.0, 90.0, 135.0, 180.0, -100.0]):
            ey, ez = cpd.pointing_error_body(c["psi"], c["theta"], roll, c["alpha_c"], c["beta_c"],
                                             c["xi"], c["phi"])
            mags.append(math.hypot(ey, ez))
        np.testing.assert_allclose(mags, mags[0], atol=1e-12)


@pytest.mark.req("OGK-CPD-007")
def test_safe_command_and_errors() -> None:
    ctl = cpd.Cpd(_config(cpd.Pointing.BODY))
    with pytest.raises(KernelError) as info:
        ctl.step(cpd.CpdInput(rate_q=math.nan))
    assert info.value.status == Status.OGK_E_NONFINITE
    assert info.value.partial.safe and info.value.partial.delta_yc == 0.0
    status, out = ctl.step_or_safe(cpd.CpdInput(theta=2 * cpd.ANGLE_LIMIT))
    assert status == Status.OGK_E_RANGE and out.safe and out.m_xc == 0.0
    assert ctl.last.safe
    assert not ctl.step(cpd.CpdInput(theta=0.2)).safe          # still usable
    bad = _config(cpd.Pointing.BODY)
    with pytest.raises(KernelError) as info:
        cpd.Cpd(bad.replace(k_dy=bad.k_py * TAU))
    assert info.value.status == Status.OGK_E_CONFIG
    with pytest.raises(KernelError) as info:
        cpd.wrap_pi(math.inf)
    assert info.value.status == Status.OGK_E_NONFINITE
    np.testing.assert_allclose(cpd.wrap_pi(np.array([3 * math.pi, -math.pi, 7.0])),
                               [math.pi, math.pi, 7.0 - 2 * math.pi], atol=1e-15)


@pytest.mark.req("OGK-CPD-012", "OGK-CPD-008")
def test_capture_study_small_dispersion() -> None:
    """Both pointing modes capture a small initial error (1 deg, 0.5 deg/s) within 10 s, and agree
    there (near zero roll the body-axis error equals the Euler differences to first order)."""
    kw = dict(n_runs=3, duration_s=10.0, sigma_angle=math.radians(1.0),
              sigma_rate=math.radians(0.5))
    body = cd.capture_study(pointing="BODY", **kw)           # type: ignore[arg-type]
    euler = cd.capture_study(pointing="EULER", **kw)         # type: ignore[arg-type]
    assert not body.lost.any() and not euler.lost.any()
    assert body.final_error_deg.max() < 1e-3
    np.testing.assert_allclose(body.max_error_deg, euler.max_error_deg, atol=0.05)


@pytest.mark.req("OGK-CPD-012")
def test_study_euler_helpers_match_scipy(rng: np.random.Generator) -> None:
    """The capture study's DCM of eq. (9) and its inverse, against scipy's intrinsic z-y-x."""
    psi, theta, phi = rng.uniform(-3, 3, 50), rng.uniform(-1.5, 1.5, 50), rng.uniform(-3, 3, 50)
    dcm = cd._euler_dcm(psi, theta, phi)
    ref = Rotation.from_euler("ZYX", np.stack([psi, theta, phi], -1)).as_matrix()
    np.testing.assert_allclose(dcm, np.swapaxes(ref, -1, -2), atol=1e-14)
    back = cd._dcm_euler(dcm)
    np.testing.assert_allclose(np.stack(back), np.stack([psi, theta, phi]), atol=1e-12)


@pytest.mark.req("OGK-CPD-012", "OGK-CPD-001")
def test_capture_study_kernel_equals_numpy_prototype() -> None:
    """The study's numpy prototype of the BODY law flies the same trajectories as the kernel (so the
    prototype's shaped variant in docs/design/cpd.md differs only by the shaping)."""
    kw = dict(n_runs=4, duration_s=8.0, seed=7)
    kernel = cd.capture_study(controller="kernel", **kw)      # type: ignore[arg-type]
    proto = cd.capture_study(controller="numpy", **kw)        # type: ignore[arg-type]
    np.testing.assert_allclose(proto.max_error_deg, kernel.max_error_deg, rtol=1e-9)
    np.testing.assert_allclose(proto.final_error_deg, kernel.final_error_deg, rtol=1e-6, atol=1e-9)
    assert kernel.max_error_deg.max() > 5.0            # a real transient, saturated


# ----------------------------------------------------------------- the typed wrapper cannot drift
@pytest.mark.req("OGK-CPD-006", "OGK-HAR-010")
def test_config_wrapper_follows_the_c_struct() -> None:
    """CpdConfig starts from ogk_cpd_config_default and knows every field of the C struct, by name."""
    from ogk_bindings._ffi import ffi, lib
    c_fields = [name for name, _ in ffi.typeof("ogk_cpd_config_t").fields]
    assert list(cpd.CpdConfig.fields()) == c_fields
    ref = ffi.new("ogk_cpd_config_t *")
    assert lib.ogk_cpd_config_default(ref) == lib.OGK_OK
    d = cpd.CpdConfig()
    for name in c_fields:                       # the defaults are C's, nothing restated in Python
        assert getattr(d, name) == getattr(ref, name), name
    assert d.pointing is cpd.Pointing.BODY
    cfg = cpd.CpdConfig(approach_accel_y=0.05, ff_period_s=0.02, ff_rate_max=0.05)
    c = cfg.to_c()                              # the fields once missing from the wrapper
    assert (c.approach_accel_y, c.ff_period_s, c.ff_rate_max) == (0.05, 0.02, 0.05)
    with pytest.raises(TypeError, match="no field 'k_pq'"):
        cpd.CpdConfig(k_pq=1.0)
    with pytest.raises(AttributeError):
        cfg.k_px = 1.0                          # immutable: replace() makes a new one
    assert cfg.replace(k_px=2.0).k_px == 2.0 and cfg.k_px == d.k_px
    assert cfg == cpd.CpdConfig(**cfg.as_dict()) and cfg != d
    cpd.Cpd(d)                                  # the defaults are a configuration init accepts


@pytest.mark.req("OGK-HAR-010")
def test_input_and_output_wrappers_match_the_c_structs() -> None:
    from ogk_bindings._ffi import ffi
    for cls, ctype in ((cpd.CpdInput, "ogk_cpd_input_t"), (cpd.CpdOutput, "ogk_cpd_output_t")):
        assert [f.name for f in dataclasses.fields(cls)] == \
            [name for name, _ in ffi.typeof(ctype).fields], ctype


@pytest.mark.req("OGK-CPD-006")
def test_reset_returns_to_the_initialised_state() -> None:
    cfg = cpd.CpdConfig(ff_period_s=0.02, ff_rate_max=0.05)
    a, b = cpd.Cpd(cfg), cpd.Cpd(cfg)
    for k in range(3):
        a.step(cpd.CpdInput(alpha_c=0.1 * k, theta=0.05))
    a.reset()
    assert a.last.safe
    inp = cpd.CpdInput(alpha_c=0.3, theta=0.1)
    assert a.step(inp) == b.step(inp)
