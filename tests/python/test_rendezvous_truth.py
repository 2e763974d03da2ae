"""Truth ("simulation") model of the rendezvous (harness/ogk/missions/rendezvous/truth.py; Starek &
Kolmanovsky 2012 secs. 3.3-3.5 with the errata to eqs. 15-18 and 22).

Validated against hand computations written here in SI: Earth's pull at its sphere of influence (on the
Sun-Earth line and at the paper's departure point), the corrected polar decomposition of eqs. (15)-(18)
against the model's vector formula at random points, solar radiation pressure at 1 AU, the unperturbed
truth against the predictive model (dynamics.rhs / throttle_rhs), DOP853 against the numpy RK4 of
dynamics.rk4_interval at small steps, the mass flow of the thrust offset, Mars' miss, the new scenario key.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from ogk.missions.rendezvous.truth import TruthModel
from ogk_bindings.errors import OgkInputError
from ogk_host.rendezvous.dynamics import Engine, rhs, rk4_interval, throttle_rhs
from ogk_host.rendezvous.scenario import load_scenario

pytestmark = pytest.mark.req("OGK-NMPC-011")

SCEN = Path(__file__).resolve().parents[2] / "scenarios"
NEP_TIME, NEP_FUEL, SEP_FUEL = (SCEN / f"rendezvous_{n}.toml" for n in ("nep_min_time", "nep_min_fuel",
                                                                         "sep_min_fuel"))
KM = 1e3
DEG = math.pi / 180.0
# Table A.1, written again here (SI).
MU_SUN = 132712440018 * KM ** 3
MU_E, MU_M = 398600.441 * KM ** 3, 42828 * KM ** 3
R_E, R_M = 149597871 * KM, 227939100 * KM
R_SOI_E = 9.24641e5 * KM
THETA_E0, THETA_M0 = -0.35414 * DEG, 130 * DEG
M0 = 1500.0


@pytest.fixture(scope="module")
def nep() -> TruthModel:
    return TruthModel.for_scenario(load_scenario(NEP_TIME), perturbed=True)


def accel_si(tm: TruthModel) -> float:
    return tm.units.length_m / tm.units.time_s ** 2


def perturbation_si(tm: TruthModel, t_s: float, r_m: float, theta: float, m_kg: float = M0
                    ) -> np.ndarray:
    u = tm.units
    x = np.array([r_m / u.length_m, theta, 0.0, 1.0, m_kg / u.mass_kg])
    return np.array(tm.perturbation(t_s / u.time_s, x)) * accel_si(tm)


def srp_si(r_m: float, m_kg: float) -> float:
    """Eq. (22) with r_hat (erratum): 2 eta S_0 / c (1 AU / r)^2 A / m, 1 AU = r_E."""
    return 2.0 * 0.6 * 1368.0 / 299792458.0 * (R_E / r_m) ** 2 * 50.0 / m_kg


def mars_polar_si(t_s: float, r_m: float, theta: float) -> np.ndarray:
    """Mars' pull (direct + indirect), the corrected polar decomposition (delta = theta_M - theta):
    d = r - r_M = (r - r_M cos delta) e_r - r_M sin delta e_theta, |d|^2 = r^2 + r_M^2 - 2 r r_M cos delta."""
    delta = THETA_M0 + math.sqrt(MU_SUN / R_M ** 3) * t_s - theta
    d3 = (r_m ** 2 + R_M ** 2 - 2.0 * r_m * R_M * math.cos(delta)) ** 1.5
    return (MU_M / d3 * np.array([R_M * math.cos(delta) - r_m, R_M * math.sin(delta)])
            - MU_M / R_M ** 2 * np.array([math.cos(delta), math.sin(delta)]))


def test_earth_pull_on_the_sun_earth_line(nep: TruthModel) -> None:
    """Spacecraft on the Sun-Earth line, outside Earth, at the sphere of influence: Earth pulls it
    towards the Sun (radially inward) with mu_E / r_SOI^2 = 4.662e-4 m/s^2, more than the engine's
    0.5 N / 1500 kg = 3.33e-4 m/s^2; the indirect term adds -mu_E / r_E^2 = -1.78e-8 m/s^2."""
    earth_pull = MU_E / R_SOI_E ** 2
    assert earth_pull == pytest.approx(4.662e-4, rel=1e-3) and earth_pull > 0.5 / M0
    r = R_E + R_SOI_E
    f = perturbation_si(nep, 0.0, r, THETA_E0)
    expected = (np.array([-earth_pull - MU_E / R_E ** 2 + srp_si(r, M0), 0.0])
                + mars_polar_si(0.0, r, THETA_E0))
    assert np.allclose(f, expected, rtol=0.0, atol=1e-14)
    assert f[0] == pytest.approx(-4.662e-4, rel=1e-3)
    # Inside the line (between the Sun and Earth): pulled outward, the same size.
    f_in = perturbation_si(nep, 0.0, R_E - R_SOI_E, THETA_E0)
    assert f_in[0] == pytest.approx(earth_pull, rel=2e-3)


def test_earth_pull_at_departure(nep: TruthModel) -> None:
    """The paper's departure point (eq. 4): Earth trails by r_SOI along the orbit, so its pull is
    backward (-e_theta), 4.66e-4 m/s^2, and slightly inward (the chord's half-angle, 0.177 deg)."""
    f = perturbation_si(nep, 0.0, R_E, 0.0) - mars_polar_si(0.0, R_E, 0.0)
    chord = 2.0 * R_E * math.sin(-THETA_E0 / 2.0)
    half = -THETA_E0 / 2.0
    expected = (-MU_E / chord ** 2 * np.array([math.sin(half), math.cos(half)])
                - MU_E / R_E ** 2 * np.array([math.cos(THETA_E0), math.sin(THETA_E0)])
                + np.array([srp_si(R_E, M0), 0.0]))
    assert np.allclose(f, expected, rtol=1e-9, atol=1e-15)
    assert f[1] == pytest.approx(-4.662e-4, rel=2e-3) and f[0] < 0.0


def test_vector_formula_equals_corrected_polar_form(nep: TruthModel) -> None:
    """Eqs. (15)-(18) corrected (sign of the cosine in the distance, cos/sin of the relative position,
    each planet's own mu) against the model's vector formula at 200 random points and times."""
    rng = np.random.default_rng(20261202)
    n_e = math.sqrt(MU_SUN / R_E ** 3)
    for _ in range(200):
        t = rng.uniform(0.0, 800.0) * 86400.0
        r = rng.uniform(0.7, 1.8) * R_E
        theta = rng.uniform(-math.pi, 3.0 * math.pi)
        m = rng.uniform(900.0, M0)
        delta = THETA_E0 + n_e * t - theta
        d3 = (r ** 2 + R_E ** 2 - 2.0 * r * R_E * math.cos(delta)) ** 1.5
        earth = (MU_E / d3 * np.array([R_E * math.cos(delta) - r, R_E * math.sin(delta)])
                 - MU_E / R_E ** 2 * np.array([math.cos(delta), math.sin(delta)]))
        expected = earth + mars_polar_si(t, r, theta) + np.array([srp_si(r, m), 0.0])
        f = perturbation_si(nep, t, r, theta, m)
        assert np.allclose(f, expected, rtol=1e-9, atol=1e-16), (t, r, theta)
    # The printed eqs. (16)-(18) differ (a planet "on the far side of the Sun"): at the departure
    # point the printed Earth term is ~1e-8 m/s^2, not 4.7e-4.
    delta = THETA_E0
    printed = MU_E / (R_E ** 2 + R_E ** 2 + 2 * R_E * R_E * math.cos(delta)) ** 1.5 * abs(
        R_E * math.sin(delta) - R_E)
    assert printed < 1e-7


def test_srp_at_one_au(nep: TruthModel) -> None:
    """2 eta S_0 / c A / m at 1 AU, 1500 kg: 1.8253e-7 m/s^2 outward; 1 / r^2 and 1 / m."""
    assert srp_si(R_E, M0) == pytest.approx(1.8253e-7, rel=1e-4)
    u = nep.units
    for r, m in ((R_E, M0), (1.5 * R_E, M0), (R_E, 750.0)):
        x = np.array([r / u.length_m, 0.0, 0.0, 1.0, m / u.mass_kg])
        assert nep.srp / (x[4] * x[0] ** 2) * accel_si(nep) == pytest.approx(srp_si(r, m), rel=1e-12)
    unpert = TruthModel.for_scenario(load_scenario(NEP_TIME), perturbed=False)
    assert unpert.perturbation(1.0, np.array([1.0, 0.0, 0.0, 1.0, 1.0])) == (0.0, 0.0)


@pytest.mark.parametrize("path", [NEP_TIME, NEP_FUEL, SEP_FUEL])
def test_unperturbed_truth_is_the_predictive_model(path: Path) -> None:
    scenario = load_scenario(path)
    tm = TruthModel.for_scenario(scenario, perturbed=False)
    engine = Engine.for_scenario(scenario)
    rng = np.random.default_rng(7)
    for _ in range(50):
        t = rng.uniform(0.0, 15.0)
        x = np.array([rng.uniform(0.8, 1.6), rng.uniform(0, 7), rng.uniform(-0.1, 0.1),
                      rng.uniform(0.7, 1.1), rng.uniform(0.6, 1.0)])
        a, w = rng.uniform(-4, 4), rng.uniform(0, 1)
        dx = tm.rhs(t, x, a, w)
        if scenario.propulsion.throttle == "constant":
            assert np.array_equal(dx, rhs(x, a, engine.thrust, engine.mass_flow))
        else:
            assert np.array_equal(dx, throttle_rhs(x, a, w, engine))
    with pytest.raises(ValueError):
        tm.rhs(0.0, tm.x0, 0.0, 1.0, angle_offset=0.01)


def test_solar_electric_engine() -> None:
    """Eq. (14), duty-cycle reading: T_max(1 AU) = T_0 = 0.5 N, mdot_max(1 AU) = 12.98 mg/s; at r_M
    (1.5237 AU) 0.2469 N; the throttle scales both."""
    scenario = load_scenario(SEP_FUEL)
    e = Engine.for_scenario(scenario)
    tm = TruthModel.for_scenario(scenario, perturbed=False)
    u = tm.units
    au = 1.495978707e11
    t1, m1 = e.limits(au / u.length_m)
    assert float(t1) * u.force_n == pytest.approx(0.5, rel=1e-12)
    assert float(m1) * u.mass_flow_kg_s == pytest.approx(12.98e-6, rel=1e-3)
    tm_, _ = e.limits(R_M / u.length_m)
    ra = R_M / au
    p = (1.1063 * ra ** 2 + 0.1495 * ra - 0.2990) / (ra ** 4 * (1 - 0.0423 * ra))
    p0_kw = (0.5e3 + 1.9137) / (36.2429 * (1.1063 + 0.1495 - 0.2990) / (1 - 0.0423))
    assert float(tm_) * u.force_n == pytest.approx((-1.9137 + 36.2429 * p0_kw * p) * 1e-3, rel=1e-12)
    assert float(tm_) * u.force_n == pytest.approx(0.2469, rel=1e-3)
    x = np.array([R_M / u.length_m, 0.0, 0.0, 0.8, 0.9])
    dx = tm.rhs(0.0, x, 0.3, 0.25)
    t_max, mdot_max = e.limits(x[0])
    assert dx[4] == pytest.approx(-0.25 * float(mdot_max), rel=1e-15)
    assert dx[2] - (x[3] ** 2 / x[0] - 1.0 / x[0] ** 2) == pytest.approx(
        0.25 * float(t_max) / x[4] * math.cos(0.3), rel=1e-12)
    # Throttle commands outside [0, 1] saturate.
    assert np.array_equal(tm.rhs(0.0, x, 0.3, 1.7), tm.rhs(0.0, x, 0.3, 1.0))
    assert tm.rhs(0.0, x, 0.3, -0.2)[4] == 0.0


@pytest.mark.parametrize("path", [NEP_TIME, SEP_FUEL])
def test_thrust_offset_and_mass_flow(path: Path) -> None:
    """Eq. (23): the perturbed engine delivers 0.9 T at its nominal Isp, so dm/dt is 0.9 x nominal
    too; the paper's accounting divides the flown fuel by 0.9. The angle offset adds to the command."""
    scenario = load_scenario(path)
    pert = TruthModel.for_scenario(scenario, perturbed=True)
    nom = TruthModel.for_scenario(scenario, perturbed=False)
    assert pert.thrust_scale == pytest.approx(0.9, rel=1e-15)
    assert pert.angle_sigma_rad == pytest.approx(3 * DEG, rel=1e-15) and nom.angle_sigma_rad == 0.0
    x = np.array([1.2, 0.5, 0.02, 0.9, 0.85])
    w = 0.6 if scenario.propulsion.throttle == "bounded" else 1.0
    d_p, d_n = pert.rhs(0.0, x, 1.0, w, 0.05), nom.rhs(0.0, x, 1.05, w)
    assert d_p[4] == pytest.approx(0.9 * d_n[4], rel=1e-14)
    f_r, f_t = pert.perturbation(0.0, x)
    grav = np.array([x[3] ** 2 / x[0] - 1.0 / x[0] ** 2, -x[3] * x[2] / x[0]])
    thrust_p = d_p[2:4] - grav - np.array([f_r, f_t])
    thrust_n = d_n[2:4] - grav
    assert np.allclose(thrust_p, 0.9 * thrust_n, rtol=1e-12, atol=0.0)
    assert math.atan2(thrust_p[1], thrust_p[0]) == pytest.approx(1.05, abs=1e-12)
    assert pert.paper_fuel_kg(450.0) == pytest.approx(500.0, rel=1e-15)


def test_propagation_matches_numpy_rk4() -> None:
    """DOP853 (rtol 1e-10) against dynamics.rk4_interval with 400 steps over one 12.3-day subinterval
    with a linear angle (RK4 error ~1e-13 at that step), and over 5 subintervals."""
    scenario = load_scenario(NEP_TIME)
    tm = TruthModel.for_scenario(scenario, perturbed=False)
    e = Engine.for_scenario(scenario)
    h = 370.0 * 86400.0 / 30 / tm.units.time_s
    alphas = [4.1, 3.5, 2.2, 1.0, 0.3, 2.9]
    x_rk = tm.x0.copy()
    for k in range(5):
        a0, a1, tk = alphas[k], alphas[k + 1], k * h

        def ctrl(t: float, a0: float = a0, a1: float = a1, tk: float = tk) -> tuple[float, float]:
            return a0 + (a1 - a0) * (t - tk) / h, 1.0

        t, states = tm.propagate(tk, x_rk, tk + h, ctrl)
        x_rk = rk4_interval(x_rk, a0, a1, h, 400, e.thrust, e.mass_flow)
        assert t[0] == tk and t[-1] == pytest.approx(tk + h, rel=1e-15)
        assert np.allclose(states[-1], x_rk, rtol=0.0, atol=1e-10), k
        x_rk = states[-1]


def test_breaks_and_soi_stop() -> None:
    """A piecewise-linear control integrated across its kinks (restarts at `breaks`) equals the
    interval-by-interval integration; the SOI event stops inside Mars' sphere of influence."""
    scenario = load_scenario(NEP_TIME)
    tm = TruthModel.for_scenario(scenario, perturbed=False)
    nodes = np.linspace(0.0, 1.2, 4)
    ang = np.array([4.0, 3.0, 3.5, 1.0])

    def ctrl(t: float) -> tuple[float]:
        return (float(np.interp(t, nodes, ang)),)

    _, whole = tm.propagate(0.0, tm.x0, 1.2, ctrl, breaks=nodes[1:-1])
    x = tm.x0
    for a, b in zip(nodes[:-1], nodes[1:]):
        x = tm.propagate(a, x, b, ctrl)[1][-1]
    assert np.allclose(whole[-1], x, rtol=0.0, atol=1e-12)
    # Coasting (bounded throttle, w = 0) on Mars' circle 2 r_SOI behind it, 1 km/s faster along the
    # track: it closes in ~6.7 d (the radial drift of the CW motion stays ~3.5e4 km) and the event fires.
    tm = TruthModel.for_scenario(load_scenario(NEP_FUEL), perturbed=False)
    mars = tm.mars_state(0.0)
    dv = 1000.0 / tm.units.velocity_m_s
    x0 = np.array([mars[0], mars[1] - 2.0 * tm.mars_soi / mars[0], 0.0, mars[3] + dv, 1.0])
    t, states = tm.propagate(0.0, x0, 1.0, lambda t: (0.0, 0.0), stop_at_mars_soi=True)
    assert t[-1] * tm.units.time_s / 86400.0 == pytest.approx(6.7, abs=0.2)
    assert tm.miss(t[-1], states[-1])[0] == pytest.approx(tm.mars_soi * tm.units.length_m, rel=1e-6)
    assert states[-1][4] == 1.0     # w = 0: no fuel
    _, free = tm.propagate(0.0, x0, 1.0, lambda t: (0.0, 0.0))
    assert free[-1][1] > states[-1][1]


def test_miss_to_mars(nep: TruthModel) -> None:
    u = nep.units
    t = 3.7
    mars = nep.mars_state(t)
    assert mars[1] == pytest.approx(THETA_M0 + math.sqrt(MU_SUN / R_M ** 3) * t * u.time_s, rel=1e-14)
    x = np.append(mars, 0.7)
    assert nep.miss(t, x) == pytest.approx((0.0, 0.0), abs=1e-6)
    # 1000 km outward and 10 m/s more radial speed: a miss of exactly that.
    y = x.copy()
    y[0] += 1e6 / u.length_m
    y[2] += 10.0 / u.velocity_m_s
    pos, vel = nep.miss(t, y)
    assert pos == pytest.approx(1e6, rel=1e-6) and vel == pytest.approx(10.0, rel=1e-6)
    earth = nep.earth_state(t)
    assert earth[1] == pytest.approx(THETA_E0 + t, rel=1e-14) and earth[0] == 1.0


def test_draw_period_key(tmp_path: Path) -> None:
    """[dispersions] thrust_angle_draw_period_s: in every rendezvous file (0 = per subinterval),
    negative or missing rejected with the key named."""
    for path in (NEP_TIME, NEP_FUEL, SEP_FUEL):
        scenario = load_scenario(path)
        assert scenario.dispersions.thrust_angle_draw_period_s == 0.0
        assert TruthModel.for_scenario(scenario, True).angle_draw_period == 0.0
    text = NEP_TIME.read_text()
    line = next(l for l in text.splitlines() if l.startswith("thrust_angle_draw_period_s"))
    for bad, needle in ((text.replace(line, "thrust_angle_draw_period_s = -1.0"), "must be >= 0"),
                        (text.replace(line, ""), "missing key")):
        path = tmp_path / "bad.toml"
        path.write_text(bad)
        with pytest.raises(OgkInputError) as info:
            load_scenario(path)
        assert info.value.key == "dispersions.thrust_angle_draw_period_s"
        assert needle in str(info.value)
