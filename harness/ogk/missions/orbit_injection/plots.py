"""PNG figures of a campaign in the spirit of the paper's Figs. 3-5 (matplotlib, Agg backend).

  <scenario>_states.png       Fig. 3: altitude error, declination, v_r, v_t, v_n and M_x vs time,
                           every recorded run overlaid, nominal dashed
  <scenario>_actuators.png    Fig. 4: nozzle deflections Delta_y, Delta_z (and M_x) vs time
  <scenario>_attitude.png     Fig. 5: commanded vs actual Psi, Theta, Phi of one run
  <scenario>_injection.png    injection errors of every run (scatter) and t_f histogram
  <scenario>_histograms.png   histogram of each injection error (log counts: the tails show), with
                           the paper's sigma and the acceptance tolerance marked
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ogk.sil.plots import dispersion_figure, pyplot, save

from .campaign import CampaignResult, tolerances
from .nominal_ref import circular_speed, nominal_reference
from .report import LABELS


def write_plots(res: CampaignResult, out_dir: str | Path) -> list[Path]:
    """Writes the PNGs that the result's data allows; returns their paths."""
    plt = pyplot()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    h = res.history
    scn = res.scenario
    ref = nominal_reference(scn)
    if h is not None and h.t_s.size:
        t = h.t_s
        d = h.data
        nom = ref.state(np.clip(t, 0.0, ref.tf_s))
        nom[t > ref.tf_s] = np.nan
        vc = circular_speed(scn)
        panels = [("r - R_f [km]", (d["r_m"] - scn.target_radius_m) / 1e3,
                   (nom[:, 0] - scn.target_radius_m) / 1e3),
                  ("declination phi [deg]", np.degrees(d["phi_rad"]), np.degrees(nom[:, 2])),
                  ("v_r [km/s]", d["vr_mps"] / 1e3, nom[:, 3] / 1e3),
                  ("v_t - v_c [km/s]", (d["vt_mps"] - vc) / 1e3, (nom[:, 4] - vc) / 1e3),
                  ("v_n [m/s]", d["vn_mps"], nom[:, 5]),
                  ("M_x [N m]", d["Mx_Nm"], None)]
        fig, axes = plt.subplots(3, 2, figsize=(11, 9), sharex=True)
        for ax, (label, val, nominal) in zip(axes.ravel(), panels):
            ax.plot(t, val, lw=0.6, alpha=0.6)
            if nominal is not None:
                ax.plot(t, nominal, "k--", lw=1.2, label="nominal")
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
        for ax in axes[-1]:
            ax.set_xlabel("time since ignition [s]")
        fig.suptitle(f"{scn.name}: state histories ({h.run_id.size} runs, "
                     f"truth {res.truth}, guidance {res.guidance})")
        fig.tight_layout()
        written.append(_save(fig, out / f"{scn.name}_states.png"))

        if res.truth == "6dof":
            fig, axes = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
            for ax, key, label, scale in [(axes[0], "Dy_rad", "Delta_y [deg]", np.degrees(1.0)),
                                          (axes[1], "Dz_rad", "Delta_z [deg]", np.degrees(1.0)),
                                          (axes[2], "Mx_Nm", "M_x [N m]", 1.0)]:
                ax.plot(t, d[key] * scale, lw=0.6, alpha=0.6)
                ax.set_ylabel(label)
                ax.grid(alpha=0.3)
            axes[-1].set_xlabel("time since ignition [s]")
            fig.suptitle("Thrust deflection angles and roll torque (actual, incl. actuation noise)")
            fig.tight_layout()
            written.append(_save(fig, out / f"{scn.name}_actuators.png"))

            fig, axes = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
            col = 0
            for ax, (act, cmd, label) in zip(axes, [("psi_rad", "psi_c_rad", "yaw Psi [deg]"),
                                                    ("theta_rad", "theta_c_rad", "pitch Theta [deg]"),
                                                    ("phi_roll_rad", "phi_c_rad", "roll Phi [deg]")]):
                ax.plot(t, np.degrees(d[cmd][:, col]), "k--", lw=1.2, label="commanded")
                ax.plot(t, np.degrees(d[act][:, col]), lw=1.0, label="actual")
                ax.set_ylabel(label)
                ax.grid(alpha=0.3)
            axes[0].legend()
            axes[-1].set_xlabel("time since ignition [s]")
            fig.suptitle(f"Commanded and actual attitude, run {int(h.run_id[col])}")
            fig.tight_layout()
            written.append(_save(fig, out / f"{scn.name}_attitude.png"))

    ok = res.flown
    if ok.any():
        fig = dispersion_figure(
            res.errors, ok, [("dr_f_m", "dvr_f_mps"), ("dvt_f_mps", "dvn_f_mps"),
                             ("dphi_f_deg", "dvn_f_mps")], LABELS, "tf_s", res.nominal_tf_s,
            f"{scn.name}: injection errors at cut-off ({int(ok.sum())} runs flown, "
            f"{res.n_failures} failed)", tolerances(scn))
        written.append(_save(fig, out / f"{scn.name}_injection.png"))
        written.append(_save(_histograms(res, ok), out / f"{scn.name}_histograms.png"))
    return written


def _histograms(res: CampaignResult, ok: np.ndarray):
    """One panel per injection error: counts on a log axis, so that a tail of a few runs in
    thousands is visible; vertical lines at +-4 paper sigmas (when known) and the tolerance."""
    plt = pyplot()
    scn = res.scenario
    keys = ("dr_f_m", "dphi_f_deg", "dvr_f_mps", "dvt_f_mps", "dvn_f_mps", "tf_s")
    sigma = dict(zip(keys, scn.paper.table7_sigma)) if scn.paper is not None else {}
    tol = tolerances(scn)
    fig, axes = plt.subplots(2, 3, figsize=(13, 7))
    for ax, key in zip(axes.ravel(), keys):
        v = res.errors[key][ok]
        centre = float(np.mean(v)) if key == "tf_s" else 0.0
        half = max(float(np.max(np.abs(v - centre))) if v.size else 0.0,
                   4.0 * sigma.get(key, 0.0)) * 1.15 or 1.0
        ax.hist(v, bins=np.linspace(centre - half, centre + half, 61), color="C0", alpha=0.8)
        ax.set_yscale("log")
        ax.set_xlim(centre - half, centre + half)
        if key in sigma:
            for sgn in (-1.0, 1.0):
                ax.axvline(centre + sgn * 4.0 * sigma[key], color="k", ls="--", lw=1.0,
                           label="4 paper sigma" if sgn > 0 else None)
        if key in tol:
            if tol[key] <= half:
                for sgn in (-1.0, 1.0):
                    ax.axvline(sgn * tol[key], color="r", ls=":", lw=1.2,
                               label="tolerance" if sgn > 0 else None)
            else:
                ax.text(0.02, 0.95, f"tolerance +-{tol[key]:.3g} (off scale)",
                        transform=ax.transAxes, fontsize=8, va="top")
        ax.set_xlabel(LABELS[key])
        ax.set_ylabel("runs")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.suptitle(f"{scn.name}: injection errors, {int(ok.sum())} runs (log counts)")
    fig.tight_layout()
    return fig


_save = save
