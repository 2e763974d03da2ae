"""One MPSP case as the JSON record of `ogk mpsp apophis`, and the side-by-side table with the paper.

The paper's numbers (Tables 3, 5, 6) are read from the scenario's [paper_results.table*] sections through
the ground scenario loader (scenario.paper_results); a scenario without them gets no paper columns.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

from ogk.missions.low_thrust_transfer.cases import TABLE_OF_KIND, MpspSetup, Case, fuel_increase_percent
from ogk.missions.low_thrust_transfer.reference import Reference
from ogk_bindings.mpsp import MpspResult

JSON_KEYS: tuple[str, ...] = ("converged", "newton_iterations", "outer_steps", "dr_f_km", "dv_f_kmps",
                              "lambda_mf", "final_mass_kg", "fuel_increase_pct", "thrust_arcs",
                              "cpu_s")


@dataclasses.dataclass(frozen=True)
class CaseRecord:
    """What `ogk mpsp apophis --case ... --json` writes (units in the names)."""

    converged: bool
    newton_iterations: int
    outer_steps: int
    dr_f_km: float
    dv_f_kmps: float
    lambda_mf: float
    final_mass_kg: float
    fuel_increase_pct: float | None  #: None when no fuel-optimal reference was computed
    thrust_arcs: int
    cpu_s: float

    def to_json(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


def make_record(setup: MpspSetup, res: MpspResult, cpu_s: float,
                reference: Reference | None) -> CaseRecord:
    m_f = res.m_f * setup.mu_kg
    fi = None
    if reference is not None:
        fi = fuel_increase_percent(m_f, reference.final_mass_kg,
                                   float(setup.scenario.spacecraft.initial_mass_kg))
    return CaseRecord(bool(res.converged), int(res.newton_iterations), int(res.outer_steps),
                      float(res.err_r * setup.lu_km), float(res.err_v * setup.vu_km_s),
                      float(res.lambda_mf), float(m_f), fi, int(res.n_thrust_arcs), float(cpu_s))


@dataclasses.dataclass(frozen=True)
class PaperRow:
    """One row of Table 3, 5 or 6."""

    position_error_km: float
    velocity_error_km_s: float
    lambda_mf: float
    newton_iterations: int
    fuel_increase_percent: float
    mpsp_time_s: float
    tpbvp_time_s: float


def paper_rows(setup: MpspSetup, cases: list[Case]) -> list[PaperRow | None]:
    """The paper's row of each case of `paper_cases` (None for a case not in the tables, every one
    None when the scenario has no [paper_results])."""
    ref = setup.scenario.paper_results or {}
    counters = {k: 0 for k in TABLE_OF_KIND}
    out: list[PaperRow | None] = []
    for case in cases:
        table = ref.get(TABLE_OF_KIND[case.kind])
        i = counters[case.kind]
        counters[case.kind] += 1
        if table is None or i >= len(table["newton_iterations"]):
            out.append(None)
            continue
        out.append(PaperRow(table["position_error_km"][i], table["velocity_error_km_s"][i],
                            table["lambda_mf"][i], int(table["newton_iterations"][i]),
                            table["fuel_increase_percent"][i], table["mpsp_time_s"][i],
                            table["tpbvp_time_s"][i]))
    return out


def _col(row: PaperRow | None, name: str) -> float | None:
    return None if row is None else float(getattr(row, name))


def _fmt(x: float | None, spec: str, width: int) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "n/a".rjust(width)
    return format(x, spec).rjust(width)


HEADER = ("case             conv arcs  NI ours/paper  |dr_f| km ours/paper   |dv_f| km/s ours/paper  "
          "|lam_mf| ours/paper   FI % ours/paper  CPU s ours / MPSP-CT paper  ref s")
#: the same table without the paper's columns (a scenario without [paper_results], a single case)
HEADER_OURS = ("case             conv arcs   NI  |dr_f| km   |dv_f| km/s   |lam_mf|     FI %     CPU s  ref s")


def header(paper_columns: bool) -> str:
    return HEADER if paper_columns else HEADER_OURS


def table_line(case: Case, rec: CaseRecord, paper: PaperRow | None,
               reference: Reference | None, paper_columns: bool = True) -> str:
    ref_s = (f"{_fmt(reference.solve_s if reference else None, '.1f', 5)}"
             f"{'*' if reference is not None and reference.from_cache else ' '}")
    if not paper_columns:
        return (f"{case.label:16s} {('yes' if rec.converged else 'NO'):>4s} {rec.thrust_arcs:4d}  "
                f"{rec.newton_iterations:3d}  {rec.dr_f_km:9.2f}  {rec.dv_f_kmps:12.2e}  "
                f"{abs(rec.lambda_mf):9.2e}  {_fmt(rec.fuel_increase_pct, '.2f', 7)}  {rec.cpu_s:8.3f}  "
                + ref_s)
    p = paper
    ni = _col(p, 'newton_iterations')
    return (f"{case.label:16s} {('yes' if rec.converged else 'NO'):>4s} {rec.thrust_arcs:4d}  "
            f"{rec.newton_iterations:3d} / {_fmt(ni, '.0f', 3)}    "
            f"{rec.dr_f_km:8.2f} / {_fmt(_col(p, 'position_error_km'), '.2f', 7)}    "
            f"{rec.dv_f_kmps:9.2e} / {_fmt(_col(p, 'velocity_error_km_s'), '.2e', 8)}   "
            f"{abs(rec.lambda_mf):8.2e} / {_fmt(_col(p, 'lambda_mf'), '.2e', 8)}  "
            f"{_fmt(rec.fuel_increase_pct, '.2f', 6)} / {_fmt(_col(p, 'fuel_increase_percent'), '.2f', 5)}  "
            f"{rec.cpu_s:8.3f} / {_fmt(_col(p, 'mpsp_time_s'), '.2f', 6)}           " + ref_s)
