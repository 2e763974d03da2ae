"""PNG figures of a campaign in the spirit of the paper's Figs. 3-5 (matplotlib, Agg backend).

  <scenario>_states.png       Fig. 3: altitude error, declination, v_r, v_t, v_n and M_x vs time,
                           every recorded run overlaid, nominal dashed
  <scenario>_actuators.png    Fig. 4: nozzle deflections Delta_y, Delta_z (and M_x) vs time
  <scenario>_attitude.png     Fig. 5: commanded vs actual Psi, Theta, Phi of one run
  <scenario>_injection.png    injection errors of every run (scatter, at the data's own scale) and
                           t_f histogram; the acceptance box is drawn when it is on scale, otherwise
                           stated in the panel with the number of runs outside it
  <scenario>_histograms.png   histogram of each injection error over the data's own range (log counts:
                           the tails show), with the paper's 4 sigma and the acceptance tolerance
                           drawn when on scale, otherwise stated in the panel
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ogk.sil.plots import pyplot, save

from .flights import CampaignResult, tolerances
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
        written.append(_save(_injection(res, ok), out / f"{scn.name}_injection.png"))
        written.append(_save(_histograms(res, ok), out / f"{scn.name}_histograms.png"))
    return written


#: A tolerance is drawn when it is at most this many times the largest |error| of the runs: beyond
#: that the data would shrink to a dot, and the tolerance is stated in the panel instead.
ON_SCALE = 3.0


def _fmt(v: float) -> str:
    return f"{v:.3g}"


def _injection(res: CampaignResult, ok: np.ndarray):
    """Three scatter panels of error pairs at the scale of the runs, and the t_f histogram."""
    plt = pyplot()
    scn = res.scenario
    tol = tolerances(scn)
    pairs = [("dr_f_m", "dvr_f_mps"), ("dvt_f_mps", "dvn_f_mps"), ("dphi_f_deg", "dvn_f_mps")]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    for ax, (kx, ky) in zip(axes.ravel(), pairs):
        x, y = res.errors[kx][ok], res.errors[ky][ok]
        ax.scatter(x, y, s=8, alpha=0.6, color="C0", label=f"{x.size} runs")
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.axvline(0.0, color="0.6", lw=0.6)
        tx, ty = tol.get(kx), tol.get(ky)
        if tx is not None and ty is not None:
            span_x = float(np.max(np.abs(x))) or tx
            span_y = float(np.max(np.abs(y))) or ty
            outside = int(np.sum((np.abs(x) > tx) | (np.abs(y) > ty)))
            if tx <= ON_SCALE * span_x and ty <= ON_SCALE * span_y:
                ax.plot([-tx, tx, tx, -tx, -tx], [-ty, -ty, ty, ty, -ty], "r--", lw=0.9,
                        label=f"acceptance ({outside} outside)")
            else:   # stated above the panel, where it hides no run
                ax.set_title(f"acceptance box |{LABELS[kx].split()[0]}| <= {_fmt(tx)}, "
                             f"|{LABELS[ky].split()[0]}| <= {_fmt(ty)}: off scale, {outside} of {x.size} "
                             "runs outside", fontsize=8.5, color="darkred")
        ax.margins(0.15)
        ax.ticklabel_format(axis="both", style="sci", scilimits=(-3, 4))
        ax.set_xlabel(LABELS[kx])
        ax.set_ylabel(LABELS[ky])
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
    ax = axes[1, 1]
    tf = res.errors["tf_s"][ok]
    ax.hist(tf, bins=min(40, max(5, int(tf.size ** 0.5))), color="C0", alpha=0.8)
    if res.nominal_tf_s is not None:
        ax.axvline(res.nominal_tf_s, color="k", ls="--", label=f"nominal t_f* {res.nominal_tf_s:.2f} s")
        ax.legend(fontsize=8)
    ax.set_xlabel(LABELS["tf_s"])
    ax.set_ylabel("runs")
    ax.grid(alpha=0.3)
    fig.suptitle(f"{scn.name}: injection errors at cut-off ({int(ok.sum())} runs flown, "
                 f"{res.n_failures} failed)")
    fig.tight_layout()
    return fig


def _histograms(res: CampaignResult, ok: np.ndarray):
    """One panel per injection error over the runs' own range: counts on a log axis, so that a tail
    of a few runs in thousands is visible; +-4 paper sigmas (when known) and the tolerance as
    vertical lines when on scale (within ON_SCALE times the data's range), stated in the panel
    otherwise."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    plt = pyplot()
    scn = res.scenario
    keys = ("dr_f_m", "dphi_f_deg", "dvr_f_mps", "dvt_f_mps", "dvn_f_mps", "tf_s")
    sigma = dict(zip(keys, scn.paper.table7_sigma)) if scn.paper is not None else {}
    tol = tolerances(scn)
    fig, axes = plt.subplots(2, 3, figsize=(13, 7))
    for ax, key in zip(axes.ravel(), keys):
        v = res.errors[key][ok]
        centre = float(np.mean(v)) if key == "tf_s" else 0.0
        data_half = float(np.max(np.abs(v - centre))) if v.size else 0.0
        marks = []   # (offset from centre, colour, style, label)
        notes = []
        if key in sigma:
            four = 4.0 * sigma[key]
            if data_half > 0.0 and four > ON_SCALE * data_half:
                notes.append(f"4 paper sigma +-{_fmt(four)} (off scale)")
            else:
                marks.append((four, "k", "--", "4 paper sigma"))
        if key in tol:
            if data_half > 0.0 and tol[key] > ON_SCALE * data_half:
                outside = int(np.sum(np.abs(v) > tol[key]))
                notes.append(f"tolerance +-{_fmt(tol[key])} (off scale, {outside} outside)")
            else:
                marks.append((tol[key], "r", ":", "tolerance"))
        half = max([data_half] + [m[0] for m in marks]) * 1.15 or 1.0
        ax.hist(v, bins=np.linspace(centre - half, centre + half, 61), color="C0", alpha=0.8)
        ax.set_yscale("log")
        ax.yaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        ax.yaxis.set_major_formatter(FuncFormatter(lambda c, _: f"{c:g}"))
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_xlim(centre - half, centre + half)
        for offset, colour, style, label in marks:
            for sgn in (-1.0, 1.0):
                ax.axvline(centre + sgn * offset, color=colour, ls=style, lw=1.1,
                           label=label if sgn > 0 else None)
        if notes:   # above the panel, where they hide no bar
            ax.set_title("\n".join(notes), fontsize=8, color="darkred")
        if marks:
            ax.legend(fontsize=8, loc="upper right")
        ax.set_xlabel(LABELS[key] if key != "tf_s" else f"{LABELS[key]} (mean {centre:.2f} s)")
        ax.set_ylabel("runs")
        ax.grid(alpha=0.3)
    fig.suptitle(f"{scn.name}: injection errors, {int(ok.sum())} runs (log counts)")
    fig.tight_layout()
    return fig


_save = save
