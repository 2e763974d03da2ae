"""The proximity family's figures (ogk.sil.plots): one flight's trajectory in the target's Hill frame
(V-bar across, R-bar up) with the keep-out discs, the plans' discs and the hold point, and its throttle
history; a campaign's final errors at the hold point against the acceptance box."""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from ogk_host.proximity.scenario import ProximityScenario

from ogk.sil.plots import dispersion_figure, pyplot, save

from .closed_loop import FlightResult


def _discs(ax: Any, scn: ProximityScenario) -> None:
    th = np.linspace(0.0, 2.0 * np.pi, 200)
    for j, k in enumerate(scn.keepouts):
        r_plan = k.radius_m + scn.guidance.keepout_margin_m
        ax.fill(k.centre_m[1] + k.radius_m * np.cos(th), k.centre_m[0] + k.radius_m * np.sin(th),
                color="tab:red", alpha=0.25, label="keep-out (truth)" if j == 0 else None)
        ax.plot(k.centre_m[1] + r_plan * np.cos(th), k.centre_m[0] + r_plan * np.sin(th), "r:", lw=0.8,
                label="keep-out (plans)" if j == 0 else None)


def trajectory_figure(scn: ProximityScenario, flights: Sequence[FlightResult], title: str) -> Any:
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(9, 5))
    _discs(ax, scn)
    for i, r in enumerate(flights):
        ax.plot(r.hill[:, 1], r.hill[:, 0], lw=0.9, label="truth" if i == 0 else None)
    if flights and flights[0].first_plan is not None:
        p = flights[0].first_plan
        ax.plot(p.states[:, 1] * scn.units.length_m, p.states[:, 0] * scn.units.length_m, "k.", ms=3,
                label="ground plan (nodes)")
    ax.plot([scn.start[1]], [scn.start[0]], "go", label="start")
    ax.plot([scn.hold_point_m[1]], [scn.hold_point_m[0]], "k*", ms=10, label="hold point")
    ax.plot([0.0], [0.0], "ks", ms=6, label="target")
    ax.set_xlabel("y, along-track (V-bar) [m]")
    ax.set_ylabel("x, radial (R-bar) [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.invert_xaxis()           # the target's velocity to the left: the chaser comes from ahead
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title)
    fig.tight_layout()
    return fig


def throttle_figure(r: FlightResult, title: str) -> Any:
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 5), sharex=True)
    a1.plot(r.t, r.command[:, 1], lw=0.9)
    a1.set_ylabel("throttle w [-]")
    a1.set_ylim(-0.05, 1.05)
    for rp in r.replans:
        a1.axvline(rp.t_s, color="0.8", lw=0.5)
    # the angle wrapped to (-180, 180], shown where the engine is on (it means nothing at w = 0)
    angle = np.degrees(np.angle(np.exp(1j * (r.command[:, 0] + r.offset))))
    a2.plot(r.t, np.where(r.command[:, 1] > 1e-3, angle, np.nan), ".", ms=2)
    a2.set_ylabel("thrust angle from R-bar [deg]\n(applied, engine on)")
    a2.set_ylim(-185, 185)
    a2.set_xlabel("t [s]")
    a2.grid(alpha=0.3)
    a1.grid(alpha=0.3)
    a1.set_title(title)
    fig.tight_layout()
    return fig


def write_flight_plots(scn: ProximityScenario, r: FlightResult, out: Path, stem: str = "flight") -> list[Path]:
    out.mkdir(parents=True, exist_ok=True)
    return [save(trajectory_figure(scn, [r], f"{scn.name}: {stem}"), out / f"{stem}_trajectory.png"),
            save(throttle_figure(r, f"{scn.name}: {stem}"), out / f"{stem}_throttle.png")]


def campaign_figure(scn: ProximityScenario, records: Sequence[dict[str, Any]], title: str) -> Any:
    keys = ("hold_error_y_m", "hold_error_x_m", "hold_error_vy_m_s", "hold_error_vx_m_s", "fuel_kg")
    done = [r for r in records if r.get("completed")]
    errors = {k: np.array([float(r[k]) for r in done]) for k in keys}
    ok = np.ones(len(done), dtype=bool)
    a = scn.acceptance
    return dispersion_figure(
        errors, ok, [("hold_error_y_m", "hold_error_x_m"), ("hold_error_vy_m_s", "hold_error_vx_m_s")],
        {"hold_error_y_m": "y - y_h [m]", "hold_error_x_m": "x - x_h [m]", "hold_error_vy_m_s": "v_y [m/s]",
         "hold_error_vx_m_s": "v_x [m/s]", "fuel_kg": "propellant [kg]"}, "fuel_kg", None, title,
        {"hold_error_y_m": a.hold_position_box_m, "hold_error_x_m": a.hold_position_box_m,
         "hold_error_vy_m_s": a.hold_velocity_box_m_s, "hold_error_vx_m_s": a.hold_velocity_box_m_s})
