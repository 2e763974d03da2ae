"""Side-by-side table of a campaign against the paper's Table 6 (single run, no dispersions) or
Table 7 (mean and standard deviation over the Monte Carlo campaign)."""
from __future__ import annotations

import math

from . import paper_tables as paper
from .campaign import CampaignResult, eq47_bounds
from .sil import ERROR_KEYS, RATE_KEYS

LABELS = {
    "dr_f_m": "dr_f [m]", "dphi_f_deg": "dphi_f [deg]", "dvr_f_mps": "dv_rf [m/s]",
    "dvt_f_mps": "dv_tf [m/s]", "dvn_f_mps": "dv_nf [m/s]", "tf_s": "t_f [s]",
    "Mx_dot_Nmps": "max |dM_x/dt| [N m/s]", "Dy_dot_degps": "max |dDelta_y/dt| [deg/s]",
    "Dz_dot_degps": "max |dDelta_z/dt| [deg/s]",
}


def _fmt(v: float | None) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    if v == 0.0:
        return "0"
    if abs(v) >= 1e4 or abs(v) < 1e-2:
        return f"{v:.3e}"
    return f"{v:.4f}"


def _table(header: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[i]) for r in [header] + rows) for i in range(len(header))]
    line = "  ".join(h.ljust(w) if i == 0 else h.rjust(w) for i, (h, w) in enumerate(zip(header, widths)))
    out = [line, "-" * len(line)]
    for r in rows:
        out.append("  ".join(c.ljust(w) if i == 0 else c.rjust(w)
                             for i, (c, w) in enumerate(zip(r, widths))))
    return out


def format_report(res: CampaignResult) -> str:
    """The text printed by `ogk mc leo-geo`."""
    lines = [f"LEO-to-GEO injection: {res.runs} run(s), seed {res.seed}, truth {res.truth}, "
             f"guidance {res.guidance}, dispersions "
             f"{'on' if res.switches.any else 'off (alignment errors only)'}",
             f"nominal t_f* = {res.nominal_tf_s:.4f} s (paper: {paper.NOMINAL_TF_TEXT_S} s); "
             f"control {res.settings.control_rate_hz:g} Hz, truth step "
             f"{res.settings.truth_step_s * 1e3:g} ms, guidance every "
             f"{res.scenario.sample_interval_s:g} s",
             f"failures: {res.n_failures}"
             + (f" {res.failure_reasons()}" if res.n_failures else ""),
             f"wall time: {res.wall_time_s:.1f} s on {res.workers} worker(s) (nominal solve "
             f"{res.nominal_solve_s:.1f} s, flight {res.flight_s:.1f} s = "
             f"{1e3 * res.flight_s / max(res.truth_steps, 1):.2f} ms per truth step; flight CPU "
             f"{res.flight_cpu_s:.1f} s)", ""]
    mean, std = res.mean(), res.std()
    if res.switches.any:
        lines.append(f"Injection errors vs {paper.CITATION}, Table 7 ({paper.TABLE7_RUNS} runs)")
        rows = [[LABELS[k], _fmt(mean[k]), _fmt(paper.TABLE7_MEAN[k]), _fmt(std[k]),
                 _fmt(paper.TABLE7_STD[k])] for k in ERROR_KEYS]
        lines += _table(["quantity", "mean (ours)", "mean (paper)", "std (ours)", "std (paper)"],
                        rows)
    else:
        lines.append(f"Injection errors vs {paper.CITATION}, Table 6 (single run)")
        single = mean if res.runs >= 1 else {}
        rows = [[LABELS[k], _fmt(single.get(k)), _fmt(paper.TABLE6_SINGLE_RUN[k])]
                for k in ERROR_KEYS]
        lines += _table(["quantity", "ours", "paper"], rows)
    bounds = eq47_bounds(res.scenario)
    top = res.max_rates_overall()
    if res.truth == "6dof":
        lines += ["", "Actuator rates vs eq. (47) bounds (largest over all runs)"]
        lines += _table(["quantity", "max (ours)", "bound eq. 47"],
                        [[LABELS[k], _fmt(top[k]), _fmt(bounds[k])] for k in RATE_KEYS])
    return "\n".join(lines)
