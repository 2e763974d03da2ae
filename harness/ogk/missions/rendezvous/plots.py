"""PNG figures of one closed-loop flight (matplotlib, Agg), after Starek & Kolmanovsky 2012:

- `<stem>_trajectory.png`: the heliocentric plane with Earth's and Mars' orbits, the flown trajectory and the
  thrust arrows at each replan (Figs. 5, 8);
- `<stem>_control.png`: commanded thrust angle (and the angle flown, noise included) and throttle against
  time (Figs. 6, 9);
- `<stem>_miss.png`: position and velocity miss to Mars at each replan, with the rendezvous thresholds
  (Figs. 7, 10).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from ogk_host.rendezvous.dynamics import DAY_S, Model
from ogk_host.rendezvous.scenario import RendezvousScenario

from ogk.sil.plots import pyplot, save

from .closed_loop import FlightResult


def _stem(result: FlightResult) -> str:
    return (f"{result.scenario}_{result.strategy}_{result.solver}_"
            f"{'perturbed_seed' + str(result.seed) if result.perturbed else 'unperturbed'}")


def write_plots(scenario: RendezvousScenario, result: FlightResult, out_dir: Path) -> list[Path]:
    plt = pyplot()

    out_dir.mkdir(parents=True, exist_ok=True)
    model = Model.for_scenario(scenario)
    units = model.units
    au = scenario.problem.earth_orbit_radius_m / units.length_m     # LU per AU-as-r_E (1)
    stem = _stem(result)
    title = (f"{result.strategy.upper()} MPC ({result.solver}), "
             f"{'perturbed, seed ' + str(result.seed) if result.perturbed else 'unperturbed'}: "
             f"{'rendezvous' if result.converged else 'NOT converged (' + result.reason + ')'} "
             f"at {result.t_f_days:.2f} d")
    paths: list[Path] = []

    # -- trajectory (Figs. 5, 8) ---------------------------------------------------------------------------
    r, th = result.states[:, 0] / au, result.states[:, 1]
    fig, ax = plt.subplots(figsize=(7.5, 7.5))
    ang = np.linspace(0.0, 2.0 * math.pi, 361)
    ax.plot(np.cos(ang), np.sin(ang), color="tab:blue", lw=0.8, label="Earth orbit")
    ax.plot(model.mars_radius / au * np.cos(ang), model.mars_radius / au * np.sin(ang), color="tab:red", lw=0.8,
            label=f"{scenario.target_name} orbit")
    ax.plot(r * np.cos(th), r * np.sin(th), color="k", lw=1.2, label="spacecraft")
    t_end = float(result.t[-1])
    mars_end = model.mars_state(t_end)
    mars_0 = model.mars_state(float(result.t[0]))
    ax.plot(*(mars_0[0] / au * np.array([math.cos(mars_0[1]), math.sin(mars_0[1])])), "o", color="tab:red",
            mfc="none", label=f"{scenario.target_name} at t_0")
    ax.plot(*(mars_end[0] / au * np.array([math.cos(mars_end[1]), math.sin(mars_end[1])])), "o",
            color="tab:red", label=f"{scenario.target_name} at the end")
    ax.plot([0.0], [0.0], "*", color="orange", ms=12)
    # thrust arrows at each replan (the commanded angle there)
    t_rep = np.array([h.t_days for h in result.history]) * DAY_S / units.time_s
    if len(t_rep) and len(result.command_t):
        rr = np.interp(t_rep, result.t, result.states[:, 0]) / au
        tt = np.interp(t_rep, result.t, result.states[:, 1])
        aa = np.interp(t_rep, result.command_t, np.unwrap(result.command_alpha))
        ux = np.cos(aa) * np.cos(tt) - np.sin(aa) * np.sin(tt)
        uy = np.cos(aa) * np.sin(tt) + np.sin(aa) * np.cos(tt)
        ax.quiver(rr * np.cos(tt), rr * np.sin(tt), ux, uy, angles="xy", scale_units="xy", scale=12.0,
                  width=0.003, color="tab:green", label="thrust at each replan")
    ax.set_aspect("equal")
    ax.set_xlabel("x [AU]")
    ax.set_ylabel("y [AU]")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(alpha=0.3)
    p = out_dir / f"{stem}_trajectory.png"
    save(fig, p, dpi=120, tight=True)
    paths.append(p)

    # -- control history (Figs. 6, 9) ----------------------------------------------------------------------
    td = result.command_t * units.time_s / DAY_S
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    a1.plot(td, np.degrees(result.command_alpha) % 360.0, ".", ms=2, label="commanded")
    if result.perturbed:
        a1.plot(td, np.degrees(result.command_alpha + result.command_offset) % 360.0, ".", ms=1.5, alpha=0.6,
                label="flown (noise included)")
    for h in result.history:
        if h.subdivided:
            a1.axvline(h.t_days, color="tab:purple", lw=0.8, ls="--")
    a1.set_ylabel("thrust angle [deg] (0 = radial out)")
    a1.set_ylim(0.0, 360.0)
    a1.legend(fontsize=7)
    a1.grid(alpha=0.3)
    a1.set_title(title, fontsize=9)
    thrust_scale = 1.0 + (scenario.perturbations.thrust_offset_percent / 100.0 if result.perturbed else 0.0)
    a2.plot(td, result.command_w * scenario.propulsion.thrust_max_n * thrust_scale, ".", ms=2)
    a2.set_ylabel("thrust [N] (T_max x throttle)")
    a2.set_xlabel("t [d]")
    a2.grid(alpha=0.3)
    p = out_dir / f"{stem}_control.png"
    save(fig, p, dpi=120, tight=True)
    paths.append(p)

    # -- miss per replan (Figs. 7, 10) ---------------------------------------------------------------------
    k = np.arange(len(result.history))
    fig, (b1, b2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    b1.semilogy(k, [h.position_miss_km for h in result.history], "o-", ms=3)
    b1.axhline(scenario.convergence.target_soi_radius_m / 1e3, color="tab:red", ls="--", lw=0.8,
               label=f"{scenario.target_name} SOI")
    b1.set_ylabel("||r - r_M|| [km]")
    b1.legend(fontsize=7)
    b1.grid(alpha=0.3, which="both")
    b1.set_title(title, fontsize=9)
    b2.semilogy(k, [h.velocity_miss_m_s for h in result.history], "o-", ms=3)
    b2.axhline(scenario.convergence.velocity_error_m_s, color="tab:red", ls="--", lw=0.8, label="1 km/s")
    b2.set_ylabel("||v - v_M|| [m/s]")
    b2.set_xlabel("replan (iteration)")
    b2.legend(fontsize=7)
    b2.grid(alpha=0.3, which="both")
    p = out_dir / f"{stem}_miss.png"
    save(fig, p, dpi=120, tight=True)
    paths.append(p)
    return paths
