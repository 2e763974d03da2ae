"""Text report of an orbit-injection campaign: the scenario flown, failures with their reasons, the
injection errors, and -- only when the scenario carries the paper's results ([paper_results]) -- the
paper's Table 6 (single run, no dispersions) or Table 7 (Monte Carlo) side by side."""
from __future__ import annotations

from ogk.sil.report import fmt as _fmt
from ogk.sil.report import table as _table

from .flights import CampaignResult, eq47_bounds, tolerances
from .sil import ERROR_KEYS, RATE_KEYS, EndGamePlan

LABELS = {
    "dr_f_m": "dr_f [m]", "dphi_f_deg": "dphi_f [deg]", "dvr_f_mps": "dv_rf [m/s]",
    "dvt_f_mps": "dv_tf [m/s]", "dvn_f_mps": "dv_nf [m/s]", "tf_s": "t_f [s]",
    "Mx_dot_Nmps": "max |dM_x/dt| [N m/s]", "Dy_dot_degps": "max |dDelta_y/dt| [deg/s]",
    "Dz_dot_degps": "max |dDelta_z/dt| [deg/s]",
}


def _end_game_text(res: CampaignResult) -> str:
    plan = EndGamePlan.of(res.scenario, res.settings)
    fine = (f" ({plan.fine_interval_s:g} s in the last {plan.fine_window_s:g} s)"
            if plan.fine_interval_s is not None else "")
    cut = "energy (ogk_cutoff)" if plan.energy_cutoff else "predicted at the samples (eq. 32)"
    eg = res.scenario.end_game
    if plan.terminal_window_s > 0.0 and eg.terminal_shaped:
        lead = f", lead {eg.terminal_shape_lead_s:g} s" if eg.terminal_shape_lead_s > 0.0 else ""
        term = (f"; last {plan.terminal_window_s:g} s: radius (gain {eg.terminal_shape_gain:g}) "
                f"and plane (gain {eg.terminal_shape_gain_normal:g}) shaped{lead}, along v_go in "
                f"the last {eg.terminal_shape_hold_s:g} s (ogk_terminal)")
    elif plan.terminal_window_s > 0.0:
        term = f"; along v_go in the last {plan.terminal_window_s:g} s (ogk_terminal)"
    else:
        term = ""
    return f"{fine}{term}; cut-off {cut}"


def format_report(res: CampaignResult) -> str:
    """The text printed by `ogk mc SCENARIO`."""
    scn = res.scenario
    paper = scn.paper
    lines = [f"{scn.name} ({res.scenario_path or 'scenario'}): orbit injection, {res.runs} run(s), "
             f"seed {res.seed}, truth {res.truth}, "
             f"guidance {res.guidance}, dispersions "
             f"{'on' if res.switches.any else 'off (alignment errors only)'}",
             f"nominal t_f* = {res.nominal_tf_s:.4f} s"
             + (f" (paper: {paper.min_time_s} s)" if paper else "") + "; "
             f"control {res.settings.control_rate_hz:g} Hz, truth step "
             f"{res.settings.truth_step_s * 1e3:g} ms, guidance every "
             f"{res.scenario.sample_interval_s:g} s" + _end_game_text(res),
             f"failures: {res.n_failures}"
             + (f" {res.failure_reasons()}" if res.n_failures else "")
             + "  (criterion: kernel error, truth validity, or |error| above "
             + ", ".join(f"{LABELS[k].split(' ')[0]} {v:.3g}" for k, v in tolerances(scn).items())
             + ")",
             f"wall time: {res.wall_time_s:.1f} s on {res.workers} worker(s) (nominal solve "
             f"{res.nominal_solve_s:.1f} s, flight {res.flight_s:.1f} s"
             + (f" = {1e3 * res.flight_s / res.truth_steps:.2f} ms per truth step"
                if res.truth_steps else "")
             + f"; flight CPU {res.flight_cpu_s:.1f} s)", ""]
    for failed in res.failures_list()[:20]:
        lines.append(f"  failed run {failed['run_id']}: {failed['reason']}")
    if res.n_failures > 20:
        lines.append(f"  ... {res.n_failures - 20} more failed runs in the JSON (failed_runs)")
    if res.n_failures:
        lines.append("")
    mean, std = res.mean(), res.std()
    p999, worst = res.tails()
    if res.switches.any:
        if paper is not None:
            p_mean, p_std = dict(zip(ERROR_KEYS, paper.table7_mean)), dict(zip(ERROR_KEYS, paper.table7_sigma))
            lines.append(f"Injection errors vs {scn.source}, {paper.monte_carlo_table} "
                         f"({paper.monte_carlo_runs} runs)")
            rows = [[LABELS[k], _fmt(mean[k]), _fmt(p_mean[k]), _fmt(std[k]), _fmt(p_std[k]),
                     _fmt(p999[k]), _fmt(worst[k]), _fmt(worst[k] / p_std[k]) if p_std[k] else "-"]
                    for k in ERROR_KEYS]
            lines += _table(["quantity", "mean (ours)", "mean (paper)", "std (ours)", "std (paper)",
                             "p99.9 |err|", "max |err|", "max/paper std"], rows)
        else:
            lines.append("Injection errors (mean, standard deviation and tails over the flown runs)")
            lines += _table(["quantity", "mean", "std", "p99.9 |err|", "max |err|"],
                            [[LABELS[k], _fmt(mean[k]), _fmt(std[k]), _fmt(p999[k]), _fmt(worst[k])]
                             for k in ERROR_KEYS])
        lines.append("(t_f: |t_f - mean t_f|; p99.9 and max over the flown runs)")
    else:
        single = mean if res.runs >= 1 else {}
        if paper is not None:
            p_single = dict(zip(ERROR_KEYS, paper.table6_final_errors))
            lines.append(f"Injection errors vs {scn.source}, {paper.single_run_table} (single run)")
            lines += _table(["quantity", "ours", "paper"],
                            [[LABELS[k], _fmt(single.get(k)), _fmt(p_single[k])] for k in ERROR_KEYS])
        else:
            lines.append("Injection errors (no dispersions)")
            lines += _table(["quantity", "ours"], [[LABELS[k], _fmt(single.get(k))] for k in ERROR_KEYS])
    bounds = eq47_bounds(res.scenario)
    top = res.max_rates_overall()
    if res.truth == "6dof":
        lines += ["", "Actuator rates vs eq. (47) bounds (largest over all runs)"]
        lines += _table(["quantity", "max (ours)", "bound eq. 47"],
                        [[LABELS[k], _fmt(top[k]), _fmt(bounds[k])] for k in RATE_KEYS])
    return "\n".join(lines)
