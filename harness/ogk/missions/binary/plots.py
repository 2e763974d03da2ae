"""PNG figures (matplotlib, Agg), after Xiong & Wang:

- `<transfer>_synodic.png`: the transfer in the synodic frame, x-y and x-z, with both bodies' impact spheres,
  the departure and target orbits, thrust arrows along the burns (Figs. 10-11);
- `<transfer>_history.png`: Jacobi constant and thrust direction against time (Fig. 12);
- `mc_convergence.png`: convergence rate per perturbation level, plain NRPC and the damped corrector beside
  the paper's Table 3, and the iterations of the converged runs (Figs. 14-16's question, in one picture).
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ogk_host.binary.dynamics import Model, jacobi

from .trajectory import Samples


def _plt() -> Any:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def transfer_figures(name: str, model: Model, samples: Samples, orbits: list[np.ndarray], lu_m: float,
                     tu_s: float, out_dir: Path, title: str) -> list[Path]:
    plt = _plt()
    out_dir.mkdir(parents=True, exist_ok=True)
    km = lu_m / 1e3
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.5))
    for ax, (i, j, label) in zip(axes, ((0, 1, "y"), (0, 2, "z"))):
        for centre, radius, colour in zip(model.body_positions, model.body_radius, ("0.45", "0.65")):
            ax.add_patch(plt.Circle((centre[i] * km, centre[j] * km), radius * km, color=colour, alpha=0.8))
        for orbit, style in zip(orbits, ("b--", "r--")):
            ax.plot(orbit[:, i] * km, orbit[:, j] * km, style, lw=0.8)
        burn = np.linalg.norm(samples.thrust, axis=1) > 0.0
        x = samples.state
        ax.plot(x[:, i] * km, x[:, j] * km, "k-", lw=1.0)
        idx = np.flatnonzero(burn)[::max(1, int(burn.sum() / 25))]
        ax.quiver(x[idx, i] * km, x[idx, j] * km, samples.thrust[idx, i], samples.thrust[idx, j], color="tab:orange",
                  scale=25, width=0.003)
        ax.plot(x[0, i] * km, x[0, j] * km, "bo")
        ax.plot(x[-1, i] * km, x[-1, j] * km, "r*", ms=10)
        ax.set_xlabel("x [km]")
        ax.set_ylabel(f"{label} [km]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    fig.suptitle(title)
    p1 = out_dir / f"{name}_synodic.png"
    fig.savefig(p1, dpi=110)
    plt.close(fig)

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
    fig.savefig(p2, dpi=110)
    plt.close(fig)
    return [p1, p2]


def mc_figure(doc: dict[str, Any], out_dir: Path) -> Path:
    plt = _plt()
    out_dir.mkdir(parents=True, exist_ok=True)
    levels = [lv["level_percent"] for lv in doc["levels"]]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.8))
    for name, style in (("nrpc", "o-"), ("lm", "s-"), ("hybrid", "d-")):
        rates = [lv["summary"][name]["converged_pct"] for lv in doc["levels"] if name in lv["summary"]]
        if rates:
            a1.plot(levels[:len(rates)], rates, style, label={"nrpc": "plain NRPC (eq. 64)", "lm": "damped (LM)",
                                                              "hybrid": "hybrid (eq. 64, then LM)"}[name])
    paper = doc.get("paper_converged_percent")
    if paper:
        a1.plot(doc["paper_levels_percent"], paper, "k^--", label="paper, Table 3")
    a1.set_xlabel("perturbation [%]")
    a1.set_ylabel("converged [%]")
    a1.set_ylim(0, 102)
    a1.grid(alpha=0.3)
    a1.legend()
    for name, colour in (("nrpc", "tab:blue"), ("lm", "tab:orange"), ("hybrid", "tab:green")):
        its = [r["results"][name]["iterations"] for lv in doc["levels"] for r in lv["runs"]
               if name in r.get("results", {}) and r["results"][name].get("converged")]
        if its:
            a2.hist(its, bins=range(0, max(its) + 2), alpha=0.6, color=colour, label=name)
    a2.set_xlabel("iterations of a converged run")
    a2.set_ylabel("runs")
    a2.legend()
    a2.grid(alpha=0.3)
    fig.suptitle(f"{doc['scenario']}: {doc['transfer']}, {doc['runs_per_level']} runs per level, seed {doc['seed']}")
    p = out_dir / "mc_convergence.png"
    fig.savefig(p, dpi=110)
    plt.close(fig)
    return p
