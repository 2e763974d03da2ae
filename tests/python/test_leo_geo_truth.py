"""Truth model of the LEO-to-GEO SIL (harness/ogk/missions/orbit_injection/truth.py) against independent references:
a Kepler propagation, a Cartesian scipy integration, closed-form roll spin-up and actuator responses,
vector constructions of the frames of eqs. (9), (49)-(52), Euler-angle kinematics (10)-(12), the
kernel's CPD geometry, and the ground nominal (host/ogk_host/orbit_injection) flown open loop."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ogk.missions.orbit_injection import truth as tm
from ogk.missions.orbit_injection.dispersions import DispersionSwitches, draw_runs
from ogk.missions.orbit_injection.guidance import GuidanceSetup, NominalOpenLoopGuidance
from ogk.missions.orbit_injection.nominal_ref import nominal_reference
from ogk.missions.orbit_injection.sil import SilSettings, _Rk4, fly_runs
from ogk_host.orbit_injection.scenario import load_scenario


@pytest.fixture(scope="module")
def scn():
    return load_scenario()


@pytest.fixture(scope="module")
def ref(scn):
    return nominal_reference(scn)


@pytest.fixture(scope="module")
def params(scn, ref):
    return tm.TruthParams.from_scenario(scn, ref.tf_s)


# ----------------------------------------------------------------- independent geometry
def rodrigues(v: np.ndarray, axis: np.ndarray, angle: float) -> np.ndarray:
    """Active rotation of vector v about unit axis by angle (right hand)."""
    return (v * math.cos(angle) + np.cross(axis, v) * math.sin(angle)
            + axis * (axis @ v) * (1.0 - math.cos(angle)))


def body_axes_in_a(psi: float, theta: float, roll: float) -> np.ndarray:
    """Rows x_b, y_b, z_b in a components, by turning the a axes: yaw about a3, pitch about the
    new y, roll about the new x (the 3-2-1 sequence of eq. 9), with Rodrigues' formula."""
    x, y, z = np.eye(3)
    x, y = rodrigues(x, z, psi), rodrigues(y, z, psi)
    x, z = rodrigues(x, y, theta), rodrigues(z, y, theta)
    y, z = rodrigues(y, x, roll), rodrigues(z, x, roll)
    return np.array([x, y, z])


def a_to_c(v_a: np.ndarray) -> np.ndarray:
    """From the definitions a1 = c2, a2 = -c3, a3 = -c1 (columns: a_i in c components)."""
    a_in_c = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]]).T
    return a_in_c @ v_a


def rtn_in_c(xi: float, phi: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r_hat = np.array([math.cos(phi) * math.cos(xi), math.cos(phi) * math.sin(xi), math.sin(phi)])
    t_hat = np.array([-math.sin(xi), math.cos(xi), 0.0])
    return r_hat, t_hat, np.cross(r_hat, t_hat)


def random_angles(rng, n):
    return dict(psi=rng.uniform(-math.pi, math.pi, n), theta=rng.uniform(-1.4, 1.4, n),
                roll=rng.uniform(-math.pi, math.pi, n), xi=rng.uniform(-0.5, 0.5, n),
                phi=rng.uniform(-0.3, 0.3, n), dy=rng.uniform(-0.05, 0.05, n),
                dz=rng.uniform(-0.05, 0.05, n))


@pytest.mark.req("OGK-NOG-019")
def test_dcm_eq9_matches_turned_axes_and_quaternion_round_trip(rng):
    a = random_angles(rng, 50)
    c = tm.dcm_body_from_a(a["psi"], a["theta"], a["roll"])
    for i in range(50):
        np.testing.assert_allclose(c[i], body_axes_in_a(a["psi"][i], a["theta"][i], a["roll"][i]),
                                   atol=1e-14)
    q = tm.quat_from_euler(a["psi"], a["theta"], a["roll"])
    np.testing.assert_allclose(np.linalg.norm(q, axis=0), 1.0, atol=1e-15)
    np.testing.assert_allclose(tm.dcm_from_quat(q), c, atol=1e-14)
    psi, theta, roll = tm.euler_from_quat(q)
    np.testing.assert_allclose(np.stack([psi, theta, roll]),
                               np.stack([a["psi"], a["theta"], a["roll"]]), atol=1e-12)


@pytest.mark.req("OGK-NOG-019", "OGK-CPD-003")
def test_thrust_angles_eqs_49_52_vs_vector_construction_and_kernel(rng):
    """alpha_a, beta_a from the rotation matrices of eqs. (49)-(52), from the quaternion path the
    truth integrates, from a vector construction, and from the kernel's ogk_cpd_thrust_angles."""
    from ogk_bindings._ffi import ffi, lib
    n = 40
    a = random_angles(rng, n)
    alpha, beta = tm.thrust_angles(a["psi"], a["theta"], a["roll"], a["xi"], a["phi"], a["dy"],
                                   a["dz"])
    x = np.zeros((tm.N_6DOF, n))
    x[tm.XI], x[tm.PHI] = a["xi"], a["phi"]
    x[tm.Q0:tm.Q3 + 1] = tm.quat_from_euler(a["psi"], a["theta"], a["roll"])
    d_rtn = np.stack(tm.thrust_direction_6dof(x, a["dy"], a["dz"]))
    out_a, out_b = ffi.new("double *"), ffi.new("double *")
    for i in range(n):
        axes = body_axes_in_a(a["psi"][i], a["theta"][i], a["roll"][i])
        d_b = np.array([math.cos(a["dz"][i]) * math.cos(a["dy"][i]), math.sin(a["dz"][i]),
                        math.cos(a["dz"][i]) * math.sin(a["dy"][i])])           # eq. (50)
        thrust_c = a_to_c(axes.T @ d_b)
        r_hat, t_hat, n_hat = rtn_in_c(a["xi"][i], a["phi"][i])
        expect = np.array([thrust_c @ r_hat, thrust_c @ t_hat, thrust_c @ n_hat])
        np.testing.assert_allclose(d_rtn[:, i], expect, atol=1e-14)
        assert alpha[i] == pytest.approx(math.atan2(expect[0], expect[1]), abs=1e-13)
        assert beta[i] == pytest.approx(math.asin(expect[2]), abs=1e-13)
        st = lib.ogk_cpd_thrust_angles(a["psi"][i], a["theta"][i], a["roll"][i], a["xi"][i],
                                       a["phi"][i], a["dy"][i], a["dz"][i], out_a, out_b)
        assert st == lib.OGK_OK
        assert out_a[0] == pytest.approx(alpha[i], abs=1e-13)
        assert out_b[0] == pytest.approx(beta[i], abs=1e-13)


@pytest.mark.req("OGK-NOG-019", "OGK-CPD-002")
def test_commanded_attitude_eqs_38_39_points_x_body_along_command(rng):
    n = 30
    a = random_angles(rng, n)
    alpha, beta = rng.uniform(-math.pi, math.pi, n), rng.uniform(-1.2, 1.2, n)
    psi_c, theta_c = tm.commanded_attitude(alpha, beta, a["xi"], a["phi"])
    for i in range(n):
        x_b = a_to_c(body_axes_in_a(psi_c[i], theta_c[i], a["roll"][i])[0])
        r_hat, t_hat, n_hat = rtn_in_c(a["xi"][i], a["phi"][i])
        u = (math.cos(beta[i]) * math.sin(alpha[i]) * r_hat
             + math.cos(beta[i]) * math.cos(alpha[i]) * t_hat + math.sin(beta[i]) * n_hat)
        np.testing.assert_allclose(x_b, u, atol=1e-14)


@pytest.mark.req("OGK-NOG-019")
def test_quaternion_kinematics_equal_euler_rates_eqs_10_12(rng, params):
    """dq/dt of the truth, mapped to Euler angles by central differences, equals eqs. (10)-(12)."""
    n = 25
    a = random_angles(rng, n)
    x = np.zeros((tm.N_6DOF, n))
    x[tm.R_], x[tm.VT] = 4.2e7, 3.0e3
    x[tm.Q0:tm.Q3 + 1] = tm.quat_from_euler(a["psi"], a["theta"], a["roll"])
    w = rng.normal(0.0, 0.3, (3, n))
    x[tm.RATE_P:tm.RATE_R + 1] = w
    out = np.empty_like(x)
    tm.rhs_6dof(params, 0.0, x, np.zeros((3, n)), None, 1.0, out)
    eps = 1e-6
    qp = x[tm.Q0:tm.Q3 + 1] + eps * out[tm.Q0:tm.Q3 + 1]
    qm = x[tm.Q0:tm.Q3 + 1] - eps * out[tm.Q0:tm.Q3 + 1]
    ep, em = np.stack(tm.euler_from_quat(qp)), np.stack(tm.euler_from_quat(qm))
    diff = np.angle(np.exp(1j * (ep - em))) / (2 * eps)          # [psi, theta, roll] rates
    roll_dot, theta_dot, psi_dot = tm.euler_rates(a["roll"], a["theta"], w[0], w[1], w[2])
    np.testing.assert_allclose(diff[0], psi_dot, rtol=1e-6, atol=1e-8)
    np.testing.assert_allclose(diff[1], theta_dot, rtol=1e-6, atol=1e-8)
    np.testing.assert_allclose(diff[2], roll_dot, rtol=1e-6, atol=1e-8)


@pytest.mark.req("OGK-NOG-019")
def test_aligned_6dof_translational_rates_equal_point_mass(rng, params):
    """Attitude along (alpha, beta) (eqs. 38-39, any roll), zero deflection: the 6-DOF and the
    point-mass right-hand sides of eqs. (3)-(6) coincide."""
    n = 30
    a = random_angles(rng, n)
    alpha, beta = rng.uniform(-1.0, 1.0, n), rng.uniform(-0.5, 0.5, n)
    x = np.zeros((tm.N_6DOF, n))
    x[tm.R_] = rng.uniform(2e7, 4.3e7, n)
    x[tm.XI], x[tm.PHI] = a["xi"], a["phi"]
    x[tm.VR:tm.VN + 1] = rng.normal(0.0, 1e3, (3, n)) + np.array([[0.0], [3e3], [0.0]])
    psi_c, theta_c = tm.commanded_attitude(alpha, beta, a["xi"], a["phi"])
    x[tm.Q0:tm.Q3 + 1] = tm.quat_from_euler(psi_c, theta_c, a["roll"])
    t = rng.uniform(0.0, 100.0)
    six, pm = np.empty_like(x), np.empty((6, n))
    tm.rhs_6dof(params, t, x, np.zeros((3, n)), None, 1.0, six)
    tm.rhs_point_mass(params, t, x[:6], alpha, beta, 1.0, pm)
    np.testing.assert_allclose(six[:6], pm, rtol=1e-12, atol=1e-12)


def spherical_to_cartesian(x6: np.ndarray) -> np.ndarray:
    r, xi, phi, vr, vt, vn = x6
    r_hat, t_hat, n_hat = rtn_in_c(xi, phi)
    return np.concatenate([r * r_hat, vr * r_hat + vt * t_hat + vn * n_hat])


def kepler_propagate(mu: float, rv0: np.ndarray, dt: float) -> np.ndarray:
    """Elliptic two-body propagation with Lagrange f, g coefficients (Kepler's equation by Newton)."""
    r0, v0 = rv0[:3], rv0[3:]
    rn = np.linalg.norm(r0)
    a = 1.0 / (2.0 / rn - v0 @ v0 / mu)
    n = math.sqrt(mu / a**3)
    sig0 = (r0 @ v0) / math.sqrt(mu * a)
    big_m = n * dt
    de = big_m
    for _ in range(50):
        f = de - (1 - rn / a) * math.sin(de) + sig0 * (1 - math.cos(de)) - big_m
        fp = 1 - (1 - rn / a) * math.cos(de) + sig0 * math.sin(de)
        de -= f / fp
    r = a + (rn - a) * math.cos(de) + sig0 * math.sqrt(a) * math.sqrt(a) * math.sin(de)
    f_l = 1 - a / rn * (1 - math.cos(de))
    g_l = dt - math.sqrt(a**3 / mu) * (de - math.sin(de))
    fd = -math.sqrt(mu * a) / (r * rn) * math.sin(de)
    gd = 1 - a / r * (1 - math.cos(de))
    return np.concatenate([f_l * r0 + g_l * v0, fd * r0 + gd * v0])


@pytest.mark.req("OGK-NOG-019")
def test_zero_thrust_matches_kepler_and_conserves_energy_momentum(params):
    """Eqs. (3)-(6) without thrust, fixed-step RK4 (h = 2 s, 4000 s) on an inclined eccentric
    orbit, against a Kepler propagation; energy and angular momentum conserved."""
    x0 = np.array([[3.0e7], [0.2], [0.1], [400.0], [3300.0], [250.0]])
    rk4 = _Rk4(x0.shape)

    def rhs(t, x, out):
        tm.rhs_point_mass(params, t, x, np.zeros(1), np.zeros(1), 0.0, out)
    x, h = x0.copy(), 2.0
    for j in range(2000):
        x = rk4.step(rhs, j * h, x, np.array([h]), h)
    got = spherical_to_cartesian(x[:, 0])
    rv0 = spherical_to_cartesian(x0[:, 0])
    expect = kepler_propagate(params.mu, rv0, 4000.0)
    np.testing.assert_allclose(got[:3], expect[:3], atol=1e-3)          # 1 mm over 4000 s
    np.testing.assert_allclose(got[3:], expect[3:], atol=1e-6)

    def energy(rv):
        return 0.5 * rv[3:] @ rv[3:] - params.mu / np.linalg.norm(rv[:3])
    assert energy(got) == pytest.approx(energy(rv0), rel=1e-12)
    np.testing.assert_allclose(np.cross(got[:3], got[3:]), np.cross(rv0[:3], rv0[3:]), rtol=1e-11)


@pytest.mark.req("OGK-NOG-019")
def test_frozen_attitude_6dof_matches_cartesian_thrusting_flight(params):
    """Zero rates and actuators at rest: the attitude stays fixed in inertial space, so the thrust
    acceleration T/m(t) acts along a fixed inertial direction. Compare eqs. (3)-(6) (spherical,
    RK4 at 20 ms) with a Cartesian integration by scipy DOP853 at rtol 1e-12 over 60 s."""
    psi, theta, roll = 0.3, -0.2, 1.0
    x = np.zeros((tm.N_6DOF, 1))
    x[:6, 0] = [4.0e7, 0.01, 0.002, 20.0, 1600.0, -5.0]
    x[tm.Q0:tm.Q3 + 1] = tm.quat_from_euler(np.array([psi]), np.array([theta]), np.array([roll]))
    direction_c = a_to_c(body_axes_in_a(psi, theta, roll)[0])
    rk4, h = _Rk4(x.shape), 0.02
    cmd = np.zeros((3, 1))
    x0 = x.copy()
    for j in range(3000):
        x = rk4.step(lambda t, xs, out: tm.rhs_6dof(params, t, xs, cmd, None, 1.0, out),
                     j * h, x, np.array([h]), h)
    np.testing.assert_allclose(x[tm.Q0:tm.Q3 + 1], x0[tm.Q0:tm.Q3 + 1], atol=1e-15)

    def cart(t, y):
        r = y[:3]
        return np.concatenate([y[3:], -params.mu * r / np.linalg.norm(r)**3
                               + float(tm.nominal_accel(params, np.array(t))) * direction_c])
    sol = solve_ivp(cart, (0.0, 60.0), spherical_to_cartesian(x0[:6, 0]), method="DOP853",
                    rtol=1e-12, atol=1e-9)
    got = spherical_to_cartesian(x[:6, 0])
    np.testing.assert_allclose(got[:3], sol.y[:3, -1], atol=1e-3)
    np.testing.assert_allclose(got[3:], sol.y[3:, -1], atol=1e-6)


@pytest.mark.req("OGK-NOG-019")
def test_pure_roll_torque_spins_up_P_as_M_over_Ix(params):
    """Constant roll torque M with I_x(t) = I_x0 + Idot_x t (eq. 53): P = M/Idot ln(1 + Idot t/I_x0)
    and Phi = (M/Idot) [(I_x0/Idot + t) ln(1 + Idot t/I_x0) - t]."""
    torque = 20.0
    x = np.zeros((tm.N_6DOF, 1))
    x[:6, 0] = [4.2e7, 0.0, 0.0, 0.0, 3000.0, 0.0]
    x[tm.Q0] = 1.0
    x[tm.ACT_MX] = torque                       # actuator already at the command
    cmd = np.array([[torque], [0.0], [0.0]])
    rk4, h = _Rk4(x.shape), 0.02
    for j in range(500):
        x = rk4.step(lambda t, xs, out: tm.rhs_6dof(params, t, xs, cmd, None, 1.0, out),
                     j * h, x, np.array([h]), h)
    t = 10.0
    i0, idot = params.inertia0[0], params.inertia_rate[0]
    log_term = math.log1p(idot * t / i0)
    assert x[tm.RATE_P, 0] == pytest.approx(torque / idot * log_term, rel=1e-12)
    assert x[tm.RATE_Q, 0] == 0.0 and x[tm.RATE_R, 0] == 0.0
    _, _, roll = tm.euler_from_quat(x[tm.Q0:tm.Q3 + 1])
    assert roll[0] == pytest.approx(torque / idot * ((i0 / idot + t) * log_term - t), rel=1e-10)


@pytest.mark.req("OGK-NOG-019")
def test_actuator_first_order_lag_then_output_saturation(params):
    """Eqs. (16)-(18): the state follows c (1 - exp(-t/tau)); the output sat(state + noise) is
    clipped at Mbar_x = 60 N m and Deltabar = 3 deg; the rate dynamics see the clipped output."""
    x = np.zeros((tm.N_6DOF, 1))
    x[:6, 0] = [4.2e7, 0.0, 0.0, 0.0, 3000.0, 0.0]
    x[tm.Q0] = 1.0
    cmd = np.array([[100.0], [0.1], [-0.02]])           # 100 N m > 60, 5.7 deg > 3 deg
    rk4, h = _Rk4(x.shape), 0.002
    for j in range(150):
        x = rk4.step(lambda t, xs, out: tm.rhs_6dof(params, t, xs, cmd, None, 1.0, out),
                     j * h, x, np.array([h]), h)
    t = 0.3
    tau = params.time_constant
    for row, k in ((tm.ACT_MX, 0), (tm.ACT_DY, 1), (tm.ACT_DZ, 2)):
        assert x[row, 0] == pytest.approx(cmd[k, 0] * (1 - math.exp(-t / tau[k])), rel=1e-9)
    mx, dy, dz = tm.actuator_outputs(params, x, None)
    assert mx[0] == 60.0 and dy[0] == pytest.approx(math.radians(3.0))
    assert dz[0] == pytest.approx(-0.02 * (1 - math.exp(-3.0)), rel=1e-9)  # inside the limit
    noisy = tm.actuator_outputs(params, x, np.array([[-50.0], [-0.08], [0.001]]))
    assert noisy[0][0] == pytest.approx(x[tm.ACT_MX, 0] - 50.0)
    assert noisy[1][0] == pytest.approx(x[tm.ACT_DY, 0] - 0.08)
    out = np.empty_like(x)
    x[tm.RATE_P:tm.RATE_R + 1] = 0.0                    # no gyroscopic terms
    tm.rhs_6dof(params, 0.0, x, cmd, None, 1.0, out)
    assert out[tm.RATE_P, 0] == pytest.approx(60.0 / params.inertia0[0])
    assert out[tm.RATE_Q, 0] == pytest.approx(
        params.thrust0 * params.arm0 * math.cos(dz[0]) * math.sin(math.radians(3.0))
        / params.inertia0[1])


@pytest.mark.req("OGK-NOG-019")
def test_thrust_fluctuation_eq55_scales_thrust_not_mass_flow(rng, params):
    coeffs = rng.normal(0.0, 0.02, (10, 7))
    t = rng.uniform(0.0, 110.0, 7)
    w = 2 * math.pi / params.fluctuation_period
    k = np.arange(1, 6)[:, None]
    expect = 1 + (coeffs[:5] * np.sin(k * w * t)).sum(0) + (coeffs[5:] * np.cos(k * w * t)).sum(0)
    np.testing.assert_allclose(tm.thrust_factor(params, t, coeffs), expect, rtol=1e-13)
    scalar = tm.thrust_factor(params, float(t[0]), coeffs)
    np.testing.assert_allclose(scalar[0], expect[0], rtol=1e-13)
    # point-mass acceleration = nominal n0 c / (c - n0 t) times the factor (mass flow nominal)
    x = np.array([[4.2e7], [0.0], [0.0], [0.0], [0.0], [0.0]])
    out = np.empty_like(x)
    tm.rhs_point_mass(params, 50.0, x, np.zeros(1), np.zeros(1), 1.03, out)
    n0, c = params.n0, params.exhaust_velocity
    assert out[tm.VT, 0] == pytest.approx(1.03 * n0 * c / (c - n0 * 50.0), rel=1e-14)
    assert params.mass_flow == pytest.approx(params.mass0 * n0 / c)


@pytest.mark.req("OGK-NOG-019")
def test_point_mass_open_loop_nominal_reproduces_ground_nominal(scn, ref):
    """The truth and the ground tools agree: u*(t) flown open loop with the point-mass truth
    (RK4, 20 ms, cut-off exactly at t_f*) lands on the ground nominal's final state."""
    sw = DispersionSwitches.none()
    draws, gens = draw_runs(scn, 0, [0], sw)
    guidance = NominalOpenLoopGuidance(GuidanceSetup(scn, ref, draws.run_id))
    res = fly_runs(scn, ref, draws, gens, sw, guidance, SilSettings(truth="point-mass"))
    assert res.failure == [""]
    assert res.errors["tf_s"][0] == ref.tf_s
    final, expect = res.final_state[0], ref.final_state
    assert abs(final[0] - expect[0]) < 1e-3                        # r [m]
    assert abs(final[1] - expect[1]) < 1e-10                       # xi [rad]
    np.testing.assert_allclose(final[3:], expect[3:], atol=1e-6)   # velocities [m/s]
    # and the nominal meets eq. (20): the injection errors are those of the integration only
    for key in ("dr_f_m", "dvr_f_mps", "dvt_f_mps"):
        assert abs(res.errors[key][0]) < 1e-3


@pytest.mark.req("OGK-NOG-019")
def test_truth_step_is_converged_by_halving(scn, ref):
    """6-DOF with every dispersion and the CPD in the loop, 30 s: halving the truth step (20 ms ->
    10 ms, control rate fixed) changes the state by far less than any reported figure."""
    sw = DispersionSwitches()
    finals = []
    for substeps in (1, 2):
        draws, gens = draw_runs(scn, 11, np.arange(3), sw)
        guidance = NominalOpenLoopGuidance(GuidanceSetup(scn, ref, draws.run_id), cutoff_s=30.0)
        res = fly_runs(scn, ref, draws, gens, sw, guidance,
                       SilSettings(truth="6dof", truth_substeps=substeps))
        assert res.failure == ["", "", ""]
        finals.append(res.final_state)
    diff = np.abs(finals[0] - finals[1])
    assert diff[:, 0].max() < 1e-3            # r [m]
    assert diff[:, 3:].max() < 1e-5           # velocities [m/s]
    assert diff[:, 2].max() < 1e-12           # phi [rad] (1e-12 rad = 0.04 mm at GEO)
