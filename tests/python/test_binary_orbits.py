"""Libration points, Lyapunov and halo orbits, monodromy and manifolds (host/ogk_host/binary/orbits.py,
manifolds.py).

Independent references: (a) the Earth-Moon L1 and L2 (mu = 0.01215058560962404, point masses) at the
published x = 0.8369151... and 1.1556821...; (b) the period of a small Earth-Moon L1 Lyapunov orbit against the
linearised 2 pi / omega_p of Szebehely / Richardson, omega_p from c2 = mu / g^3 + (1 - mu) / (1 - g)^3 written
out here; (c) a finite-amplitude published case: two Earth-Moon L2 southern halo orbits of the JPL Three-Body
Periodic Orbits catalogue (ssd.jpl.nasa.gov/tools/periodic_orbits.html, the catalogue's Earth-Moon mu above),
whose initial states and periods we read as quoted in two unrelated public repositories (a Python CR3BP
propagator test: "ID723 in southern halo"; a MATLAB study: the 9:2 NRHO "Lunar Gateway ICs"); corrected with z0
held, both periods agree to < 1e-10 and the published states lie on the corrected orbits; (d) a halo orbit
re-propagated over one period by the vectorised right-hand side (not the one used to correct it) returns
to its start within 1e-9; its monodromy has the reciprocal saddle pair, the unit-modulus centre pair and the
two unit eigenvalues, det 1, and equals the symmetry product of the half-period STM; (e) a manifold state
x0 + d w_u leaves the orbit by lambda_u d per period; the realms the "+"/"-" branches enter follow the paper's
sign example; (f) the scenario's Moshup orbits exist, are periodic, have the requested amplitudes and
branches and stay outside both impact spheres.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ogk_host.binary import dynamics as dyn
from ogk_host.binary.dynamics import Model, model_from_scenario
from ogk_host.binary.manifolds import (REALM_OF_SIGN, departure_growth, manifold_states, propagate_to_cut,
                                       realm_cut,
                                       realm, transported_eigenvectors)
from ogk_host.binary.orbits import (collinear_points, continue_family, correct_orbit, flow, flow_stm,
                                    halo_bifurcation, jacobi_at_point, linear_modes, lyapunov_orbit,
                                    scenario_orbit)
from ogk_host.binary.scenario import load_scenario

pytestmark = pytest.mark.req("OGK-BLT-009")

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "moshup.toml"
MU_EM = 0.01215058560962404
EM = Model(mu=MU_EM)
#: Earth-Moon L2 southern halos of the JPL catalogue: (x0, z0, vy0, period) -- see the module docstring.
JPL_L2_SOUTH = [(1.0134037728554581, -0.1753622728109184, -0.083688427472776439, 1.3960732332950263),
                (1.02202108343387, -0.182096487798513, -0.103255420206012, 1.51110546287394)]
#: Collinear points of the Moshup model with the degree-2 terms (reported to the kernel, docs/design/blt-ground.md).
MOSHUP_POINTS = {"L1": 0.70165521552681, "L2": 1.23682408043004, "L3": -1.02415660779861}


@pytest.fixture(scope="module")
def scenario():
    return load_scenario(SCENARIO)


@pytest.fixture(scope="module")
def moshup_orbits(scenario):
    model = model_from_scenario(scenario)
    return {name: scenario_orbit(scenario, name, model) for name in scenario.orbits}


# ---------------------------------------------------------------------------------------- libration points

def test_earth_moon_collinear_points() -> None:
    pts = collinear_points(EM)
    assert pts["L1"] == pytest.approx(0.8369151, abs=1e-7)
    assert pts["L2"] == pytest.approx(1.1556821, abs=1e-7)
    for p in ("L1", "L2", "L3"):
        xl = np.array([pts[p], 0.0, 0.0, 0.0, 0.0, 0.0])
        assert np.max(np.abs(dyn.gravity_derivative(EM, xl))) < 1e-14


def test_moshup_points_with_degree2_terms(scenario) -> None:
    model = model_from_scenario(scenario)
    pts = collinear_points(model)
    point_mass = collinear_points(model_from_scenario(scenario, gravity="point-mass"))
    for p, x in MOSHUP_POINTS.items():
        assert pts[p] == pytest.approx(x, abs=1e-13)
        assert abs(pts[p] - point_mass[p]) > 1e-3          # the degree-2 terms move every point
        state = np.array([pts[p], 0.0, 0.0, 0.0, 0.0, 0.0])
        assert np.max(np.abs(dyn.gravity_derivative(model, state))) < 1e-13
    # the necks: C(L1) > C(L2) > C(L3)
    assert jacobi_at_point(model, "L1") > jacobi_at_point(model, "L2") > jacobi_at_point(model, "L3")


def test_small_lyapunov_period_is_the_linear_one() -> None:
    g = 1.0 - MU_EM - 0.8369151257723572           # L1's distance from the Moon
    c2 = MU_EM / g ** 3 + (1.0 - MU_EM) / (1.0 - g) ** 3
    omega_p = math.sqrt((2.0 - c2 + math.sqrt(9.0 * c2 * c2 - 8.0 * c2)) / 2.0)
    lam = math.sqrt((c2 - 2.0 + math.sqrt(9.0 * c2 * c2 - 8.0 * c2)) / 2.0)
    lm = linear_modes(EM, "L1")
    assert lm.planar_frequency == pytest.approx(omega_p, rel=1e-12)
    assert lm.saddle_rate == pytest.approx(lam, rel=1e-12)
    assert lm.vertical_frequency == pytest.approx(math.sqrt(c2), rel=1e-12)
    orbit = lyapunov_orbit(EM, "L1", 1e-4)
    assert orbit.period == pytest.approx(2.0 * math.pi / omega_p, rel=2e-6)
    assert orbit.amplitude == pytest.approx(1e-4, rel=1e-9)


@pytest.mark.parametrize("x0,z0,vy0,period", JPL_L2_SOUTH)
def test_published_earth_moon_l2_southern_halo(x0: float, z0: float, vy0: float, period: float) -> None:
    published = np.array([x0, 0.0, z0, 0.0, vy0, 0.0])
    orbit = correct_orbit(EM, "halo", "L2", published, period, fix="z0")
    assert orbit.period == pytest.approx(period, rel=1e-10)
    assert orbit.branch == "south" and orbit.amplitude == pytest.approx(abs(z0), rel=1e-10)
    # the stored start is the other crossing (smaller x); half a period later: the published state
    assert np.max(np.abs(flow(EM, orbit.state0, 0.5 * orbit.period) - published)) < 1e-9


def test_pseudo_arclength_lyapunov_family() -> None:
    start = lyapunov_orbit(EM, "L1", 0.005)
    v0 = np.array([start.state0[0], 0.0, start.state0[4], 0.5 * start.period])
    members = continue_family(EM, "lyapunov", v0, [-1.0, 0.0, 1.0, 0.0], 0.01, 5)
    amps, jacs = [], []
    for v in members:
        s = flow(EM, [v[0], 0.0, 0.0, 0.0, v[2], 0.0], v[3])
        assert abs(s[1]) < 1e-9 and abs(s[3]) < 1e-9            # perpendicular crossing at T/2
        amps.append(0.5 * abs(s[0] - v[0]))
        jacs.append(float(dyn.jacobi(EM, [v[0], 0.0, 0.0, 0.0, v[2], 0.0])))
    assert all(b > a for a, b in zip([start.amplitude] + amps, amps))     # growing along the family
    assert all(b < a for a, b in zip(jacs, jacs[1:]))                      # and falling in C


def test_halo_bifurcation_is_a_unit_vertical_multiplier() -> None:
    ax, v = halo_bifurcation(EM, "L1")
    state = np.array([v[0], 0.0, 0.0, 0.0, v[2], 0.0])
    _, mono = flow_stm(EM, state, 2.0 * v[3])
    assert mono[2, 2] + mono[5, 5] == pytest.approx(2.0, abs=1e-5)
    assert 0.01 < ax < 0.05


# ---------------------------------------------------------------------------------------- halos and monodromy

def test_halo_is_periodic_and_its_monodromy(moshup_orbits) -> None:
    for name in ("l1_halo_south", "l2_halo_south"):
        orbit = moshup_orbits[name]
        model = orbit.model
        sol = solve_ivp(lambda t, x: dyn.state_derivative(model, t, x), (0.0, orbit.period), orbit.state0,
                        method="DOP853", rtol=1e-12, atol=1e-13)
        assert np.max(np.abs(sol.y[:, -1] - orbit.state0)) < 1e-9, name
        fl = orbit.floquet
        vals = fl.eigenvalues
        assert fl.unstable_value * fl.stable_value == pytest.approx(1.0, abs=1e-6)
        assert np.all(np.abs(fl.unit_values - 1.0) < 1e-4)
        assert abs(np.prod(fl.unit_values) - 1.0) < 1e-8
        assert np.allclose(np.abs(fl.other_values), 1.0, atol=1e-7)     # the centre pair
        assert abs(np.prod(vals) - 1.0) < 1e-6                          # det M = 1 (symplectic)
        assert fl.stability_index > 1.0
        # the symmetry y -> -y, t -> -t: M = Sigma Phi(T/2)^-1 Sigma Phi(T/2)
        sigma = np.diag([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])
        _, phi_h = flow_stm(model, orbit.state0, 0.5 * orbit.period)
        m_sym = sigma @ np.linalg.solve(phi_h, sigma @ phi_h)
        assert np.max(np.abs(m_sym - orbit.monodromy)) < 1e-6 * np.max(np.abs(orbit.monodromy))


def test_moshup_scenario_orbits(scenario, moshup_orbits) -> None:
    lu = scenario.units.length_m
    radius = model_from_scenario(scenario).body_radius
    for name, spec in scenario.orbits.items():
        orbit = moshup_orbits[name]
        assert orbit.family == spec.family and orbit.point == spec.point and orbit.branch == spec.branch
        assert orbit.amplitude * lu == pytest.approx(spec.amplitude_m, rel=1e-9)
        back = flow(orbit.model, orbit.state0, orbit.period)
        assert np.max(np.abs(back - orbit.state0)) < 1e-9, name
        d1, d2 = orbit.min_distances()
        assert d1 > 1.5 * radius[0] and d2 > 1.3 * radius[1], name      # clear of both impact spheres
        c = dyn.jacobi(orbit.model, orbit.states(8)[1])
        assert np.max(np.abs(c - orbit.jacobi)) < 1e-10
        assert orbit.jacobi < jacobi_at_point(orbit.model, orbit.point)  # the neck at its point is open
        assert orbit.floquet.unstable_value > 100.0


# ---------------------------------------------------------------------------------------- manifolds

def test_manifold_leaves_at_the_unstable_rate(moshup_orbits) -> None:
    for name in ("l1_lyapunov", "l2_halo_south"):
        orbit = moshup_orbits[name]
        lam = orbit.floquet.unstable_value
        assert departure_growth(orbit) == pytest.approx(lam, rel=1e-4), name
        assert departure_growth(orbit, stable=True) == pytest.approx(lam, rel=1e-4), name  # backward in time


def test_manifold_states_eq_34_and_35(moshup_orbits) -> None:
    orbit = moshup_orbits["l1_lyapunov"]
    phases = np.array([0.0, 0.3, 1.1])
    states, wu, ws = transported_eigenvectors(orbit, phases)
    assert np.allclose(states[0], orbit.state0, atol=1e-15)
    assert np.allclose(wu[0], orbit.floquet.unstable_vector, atol=1e-15)
    assert np.allclose(np.linalg.norm(wu, axis=1), 1.0) and np.allclose(np.linalg.norm(ws, axis=1), 1.0)
    # w_u(tau) is the monodromy eigenvector of the orbit started at x(tau)
    _, phi = flow_stm(orbit.model, states[2], orbit.period)
    assert np.linalg.norm(phi @ wu[2] - orbit.floquet.unstable_value * wu[2]) < 1e-5 * orbit.floquet.unstable_value
    d = 1e-6
    x34 = manifold_states(orbit, phases, stable=False, sign=-1, deviation=d)
    assert np.allclose(x34, states - d * wu, atol=1e-16)
    x35 = manifold_states(orbit, phases, stable=True, sign=1, deviation=d, velocity_only=True)
    assert np.allclose(x35[:, 0:3], states[:, 0:3], atol=0.0)
    assert np.allclose(np.linalg.norm(x35[:, 3:6] - states[:, 3:6], axis=1), d, rtol=1e-9)


def test_manifold_realms_follow_the_papers_sign(moshup_orbits) -> None:
    """Sec. III.C.2: at L1, "+" leads into the primary's realm P, "-" into the secondary's realm S; at L2,
    "+" into S and "-" into the exterior realm. Unstable branches forward, stable ones backward, until the cut
    through the body that realm holds (x = -mu or x = 1 - mu; the exterior branch: x = x_L2 + 0.5 or 12 TU,
    it may turn back before the cut and sweep round outside both bodies), or an impact."""
    for name in ("l1_lyapunov", "l2_lyapunov"):
        orbit = moshup_orbits[name]
        model = orbit.model
        phases = np.linspace(0.0, orbit.period, 4, endpoint=False)
        for sign in (1, -1):
            expected = REALM_OF_SIGN[(orbit.point, sign)]
            cut = realm_cut(model, expected)
            for stable in (False, True):
                for x in manifold_states(orbit, phases, stable=stable, sign=sign):
                    end = propagate_to_cut(model, x, cut, backward=stable, t_max=12.0)
                    assert end.reached_cut or end.impact is not None or expected == "exterior", (name, sign, stable)
                    assert realm(model, end.state[0:3]) == expected, (name, sign, stable)
                    if end.impact is not None:
                        assert end.impact == {"P": 0, "S": 1}[expected]
