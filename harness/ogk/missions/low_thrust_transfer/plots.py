"""Figures of `ogk mpsp apophis --plots DIR` (matplotlib, Agg backend, PNG).

thrust_<kind>.png : throttle vs time of the nominal, the MPSP solution and the re-optimised (fuel-optimal)
                    solution of each case of a group, one panel per case (as the paper's Figs. 4, 7, 10).
angles_<kind>.png : in-plane alpha = atan2(lambda_v2, lambda_v1) in [0, 360) deg and out-of-plane
                    beta = asin(lambda_v3 / |lambda_v|) (eq. 17) of the converged MPSP solutions and the
                    nominal (Figs. 3, 6, 9).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ogk_bindings.mpsp import MpspResult

from ogk.sil.plots import pyplot, save

from .cases import KINDS, Case, MpspSetup
from .reference import Reference

F64 = NDArray[np.float64]


def _days(setup: MpspSetup) -> float:
    return float(setup.scenario.units.time_s) / 86400.0


def _arc_steps(arcs: list[tuple[float, float, float]]) -> tuple[F64, F64]:
    """Step-plot points (t, u) of (t_start, t_end, throttle) arcs."""
    t = [a[0] for a in arcs] + [arcs[-1][1]]
    u = [a[2] for a in arcs] + [arcs[-1][2]]
    return np.asarray(t), np.asarray(u)


def mpsp_throttle(setup: MpspSetup, case: Case, res: MpspResult) -> tuple[F64, F64]:
    """(t [TU], u) of the MPSP solution flown by the kernel."""
    traj = setup.guidance.propagate(res.weights, res.lambda_m0, case.x0, case.thrust_scale)
    return traj.t, traj.mode.astype(np.float64)


def thrust_angles_deg(lam_v: F64) -> tuple[F64, F64]:
    """alpha in [0, 360), beta in [-90, 90] [deg] of lambda_v (eq. 17, quadrant resolved)."""
    alpha = np.degrees(np.mod(np.arctan2(lam_v[:, 1], lam_v[:, 0]), 2.0 * np.pi))
    beta = np.degrees(np.arcsin(np.clip(lam_v[:, 2] / np.linalg.norm(lam_v, axis=1), -1.0, 1.0)))
    return alpha, beta


def write_plots(setup: MpspSetup, runs: list[tuple[Case, MpspResult, Reference | None]],
                out_dir: Path) -> list[Path]:
    plt = pyplot()
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    day = _days(setup)
    nominal_arcs = [(a.t_start, a.t_end, a.throttle) for a in setup.nominal.arcs]
    tn, un = _arc_steps(nominal_arcs)
    t_grid = np.linspace(0.0, setup.problem.final_time, 2001)
    from ogk_host.low_thrust_transfer import fourier
    t_nom, lam_nom = fourier.nominal_control_on_grid(setup.scenario, setup.nominal)
    a_nom, b_nom = thrust_angles_deg(lam_nom)
    written: list[Path] = []
    for kind in KINDS:
        group = [r for r in runs if r[0].kind == kind]
        if not group:
            continue
        fig, axes = plt.subplots(len(group), 1, figsize=(8.0, 1.1 * len(group) + 1.0), sharex=True,
                                 squeeze=False)
        for ax, (case, res, ref) in zip(axes[:, 0], group):
            ax.step(tn * day, un, where="post", color="0.5", ls="-.", lw=1.0, label="nominal")
            t_m, u_m = mpsp_throttle(setup, case, res)
            ax.step(t_m * day, u_m, where="post", color="tab:blue", lw=1.2, label="MPSP")
            if ref is not None:
                tr, ur = _arc_steps(list(ref.arcs))
                ax.step(tr * day, ur, where="post", color="tab:red", ls="--", lw=1.0,
                        label="fuel-optimal")
            ax.set_ylim(-0.15, 1.15)
            ax.set_yticks([0, 1])
            ax.set_ylabel(case.label.split(" ", 1)[1], rotation=0, ha="right", va="center",
                          fontsize=8)
        axes[0, 0].legend(loc="upper center", bbox_to_anchor=(0.5, 1.9), ncol=3, fontsize=8)
        axes[-1, 0].set_xlabel("time [days]")
        fig.suptitle(f"Thrust sequences, {kind} perturbations (throttle u)", y=0.995)
        fig.tight_layout()
        path = out_dir / f"thrust_{kind}.png"
        save(fig, path)
        written.append(path)

        fig, (ax_a, ax_b) = plt.subplots(2, 1, figsize=(8.0, 6.0), sharex=True)
        for case, res, _ in group:
            if not res.converged:
                continue
            lam_v, _ = setup.guidance.control(res.weights, t_grid)
            alpha, beta = thrust_angles_deg(lam_v)
            ax_a.plot(t_grid * day, alpha, lw=0.8, label=case.label.split(" ", 1)[1])
            ax_b.plot(t_grid * day, beta, lw=0.8)
        ax_a.plot(t_nom * day, a_nom, color="k", ls="--", lw=1.2, label="nominal")
        ax_b.plot(t_nom * day, b_nom, color="k", ls="--", lw=1.2)
        ax_a.set_ylabel("alpha [deg]")
        ax_b.set_ylabel("beta [deg]")
        ax_b.set_xlabel("time [days]")
        ax_a.legend(fontsize=7, ncol=4)
        fig.suptitle(f"Thrust angles of the converged MPSP solutions, {kind} perturbations")
        fig.tight_layout()
        path = out_dir / f"angles_{kind}.png"
        save(fig, path)
        written.append(path)
    return written
