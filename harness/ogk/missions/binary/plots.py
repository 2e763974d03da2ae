"""PNG figures (matplotlib, Agg), after Xiong & Wang:

- `<transfer>_synodic.png`: the transfer in the synodic frame, x-y and x-z, with both bodies' impact spheres,
  the departure and target orbits, thrust arrows along the burns (Figs. 10-11); each panel is zoomed on the
  transfer with a margin (`zoom_limits`), a body near it is kept whole, one far from it is named above the
  panel with its position;
- `<transfer>_history.png`: Jacobi constant and thrust direction against time (Fig. 12);
- `mc_convergence.png`: convergence rate per perturbation level, every corrector beside the paper's Table 3,
  and the iterations of the converged runs, the correctors' bars side by side (Figs. 14-16's question, in one
  picture).
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ogk_host.binary.dynamics import Model, jacobi

from ogk.sil.plots import pyplot, save

from .trajectory import Samples


#: Margin around the transfer, as a fraction of its larger extent in the panel.
ZOOM_MARGIN = 0.15
#: The departure and target orbits are inside the view when they are at most this many times the transfer's
#: extent (a halo or Lyapunov orbit at the end of a transfer), clipped otherwise (a wide circular orbit).
ORBIT_IN_VIEW = 2.0
#: A body whose impact sphere comes within this fraction of the transfer's extent of the zoomed box is
#: drawn whole (the view widens to hold it); a farther one is named above the panel instead.
NEAR_BODY = 0.5


def zoom_limits(points: np.ndarray, centres: np.ndarray, radii: np.ndarray,
                names: tuple[str, ...]) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """(lower, upper, notes) of a 2-D view of `points` (n, 2): their box with ZOOM_MARGIN, widened to hold
    each body (centre (2,), radius) that is near (NEAR_BODY); `notes` name the bodies left out."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    extent = float(np.max(hi - lo)) or float(np.max(radii)) or 1.0
    pad = ZOOM_MARGIN * extent
    lo, hi = lo - pad, hi + pad
    notes = []
    for centre, radius, name in zip(centres, radii, names):
        gap = float(np.linalg.norm(np.maximum(0.0, np.maximum(lo - centre, centre - hi)))) - radius
        if gap <= NEAR_BODY * extent:
            lo = np.minimum(lo, centre - radius - 0.25 * pad)
            hi = np.maximum(hi, centre + radius + 0.25 * pad)
        else:
            notes.append(f"{name} off the plot, at ({centre[0]:.2f}, {centre[1]:.2f}) km")
    return lo, hi, notes


def transfer_figures(name: str, model: Model, samples: Samples, orbits: list[np.ndarray], lu_m: float,
                     tu_s: float, out_dir: Path, title: str) -> list[Path]:
    plt = pyplot()
    out_dir.mkdir(parents=True, exist_ok=True)
    km = lu_m / 1e3
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.5))
    names = ("primary", "secondary")
    for ax, (i, j, label) in zip(axes, ((0, 1, "y"), (0, 2, "z"))):
        centres = np.array([[c[i] * km, c[j] * km] for c in model.body_positions])
        radii = np.asarray(model.body_radius) * km
        for centre, radius, colour, body in zip(centres, radii, ("0.45", "0.65"), names):
            ax.add_patch(plt.Circle(tuple(centre), radius, color=colour, alpha=0.8,
                                    label=f"{body} (impact sphere)"))
        x = samples.state
        for orbit in orbits:   # the orbit the transfer leaves (blue) or reaches (red): the nearer end
            leaves = (np.min(np.linalg.norm(orbit[:, :3] - x[0, :3], axis=1))
                      <= np.min(np.linalg.norm(orbit[:, :3] - x[-1, :3], axis=1)))
            ax.plot(orbit[:, i] * km, orbit[:, j] * km, "b--" if leaves else "r--", lw=0.8,
                    label="departure orbit" if leaves else "target orbit")
        burn = np.linalg.norm(samples.thrust, axis=1) > 0.0
        ax.plot(x[:, i] * km, x[:, j] * km, "k-", lw=1.0, label="transfer")
        idx = np.flatnonzero(burn)[::max(1, int(burn.sum() / 25))]
        ax.quiver(x[idx, i] * km, x[idx, j] * km, samples.thrust[idx, i], samples.thrust[idx, j], color="tab:orange",
                  scale=25, width=0.003, label="thrust direction")
        ax.plot(x[0, i] * km, x[0, j] * km, "bo", label="departure")
        ax.plot(x[-1, i] * km, x[-1, j] * km, "r*", ms=10, label="arrival")
        view = [x[:, [i, j]] * km]
        extent = float(np.max(np.ptp(view[0], axis=0)))
        view += [o[:, [i, j]] * km for o in orbits
                 if float(np.max(np.ptp(o[:, [i, j]] * km, axis=0))) <= ORBIT_IN_VIEW * extent]
        lo, hi, notes = zoom_limits(np.vstack(view), centres, radii, names)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        if notes:
            ax.set_title("; ".join(notes), fontsize=8)
        ax.set_xlabel("x [km]")
        ax.set_ylabel(f"{label} [km]")
        ax.set_aspect("equal", adjustable="box")   # the zoomed limits stay; the panel takes their shape
        ax.grid(alpha=0.3)
    axes[1].legend(fontsize=7, loc="upper center", ncol=3, bbox_to_anchor=(0.5, -0.32))   # below the panel: no data hidden
    fig.suptitle(title)
    p1 = out_dir / f"{name}_synodic.png"
    save(fig, p1)

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    hours = samples.time * tu_s / 3600.0
    a1.plot(hours, jacobi(model.gravity_only(), samples.state), "k-")
    a1.set_ylabel("Jacobi constant C_J [-]")
    a1.grid(alpha=0.3)
    for c, lab in zip(range(3), ("u_x", "u_y", "u_z")):
        a2.plot(hours, samples.thrust[:, c], label=lab)
    a2.set_ylabel("thrust direction (synodic)")
    a2.set_xlabel("time since departure [h]")
    a2.legend()
    a2.grid(alpha=0.3)
    fig.suptitle(title)
    p2 = out_dir / f"{name}_history.png"
    save(fig, p2)
    return [p1, p2]


def mc_figure(doc: dict[str, Any], out_dir: Path) -> Path:
    plt = pyplot()
    out_dir.mkdir(parents=True, exist_ok=True)
    levels = [lv["level_percent"] for lv in doc["levels"]]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.8))
    # the correctors often agree (100 % at every level): larger hollow markers under smaller ones, so that
    # each stays visible where the lines coincide
    for name, style, size, fill in (("nrpc", "o-", 11, "none"), ("lm", "s-", 7, "none"), ("hybrid", "d-", 4, None)):
        rates = [lv["summary"][name]["converged_pct"] for lv in doc["levels"] if name in lv["summary"]]
        if rates:
            a1.plot(levels[:len(rates)], rates, style, ms=size, mfc=fill, mew=1.3,
                    label={"nrpc": "plain NRPC (eq. 64)", "lm": "damped (LM)",
                           "hybrid": "hybrid (eq. 64, then LM)"}[name])
    paper = doc.get("paper_converged_percent")
    if paper:
        a1.plot(doc["paper_levels_percent"], paper, "k^--", label="paper, Table 3")
    a1.set_xlabel("perturbation [%]")
    a1.set_ylabel("converged [%]")
    a1.set_ylim(0, 102)
    a1.grid(alpha=0.3)
    a1.legend()
    # one group of bars per iteration count, the correctors side by side (overlaid bars hid one another)
    shown = []
    for name, colour in (("nrpc", "tab:blue"), ("lm", "tab:orange"), ("hybrid", "tab:green")):
        its = [int(r["results"][name]["iterations"]) for lv in doc["levels"] for r in lv["runs"]
               if name in r.get("results", {}) and r["results"][name].get("converged")]
        if its:
            shown.append((name, colour, np.bincount(its)))
    width = 0.8 / max(len(shown), 1)
    for k, (name, colour, counts) in enumerate(shown):
        at = np.arange(counts.size) + (k - (len(shown) - 1) / 2.0) * width
        a2.bar(at[counts > 0], counts[counts > 0], width=width, color=colour, label=f"{name} ({counts.sum()} runs)")
    a2.xaxis.get_major_locator().set_params(integer=True)
    a2.set_xlabel("iterations of a converged run")
    a2.set_ylabel("runs")
    a2.legend()
    a2.grid(alpha=0.3)
    per_level = [len(lv["runs"]) for lv in doc["levels"] if isinstance(lv.get("runs"), list)]
    runs = (f"{sum(per_level)} runs, {min(per_level)}-{max(per_level)} per level"
            if per_level and min(per_level) != max(per_level) else f"{doc['runs_per_level']} runs per level")
    fig.suptitle(f"{doc['scenario']}: {doc['transfer']}, {runs}, seed {doc['seed']}")
    p = out_dir / "mc_convergence.png"
    save(fig, p)
    return p
