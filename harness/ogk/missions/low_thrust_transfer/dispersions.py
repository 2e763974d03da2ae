"""The low-thrust transfer family's dispersions (Wang & Topputo 2020, secs. 4.2-4.4; family.py):
`--cases dispersed` flies on run i one perturbation of kind i mod 3 (initial state, target,
thrust) drawn uniformly within the range its [dispersions] list spans; `--cases paper` flies the
listed cases in order (Tables 3, 5, 6), nothing drawn. And how a campaign's records show them
(ogk.sil.dispersion_check).

Records (naming rule disp.<[dispersions] key>), each *as applied*, recovered from the problem the
kernel is given against the nominal one, None on a run of another kind:
  disp.initial.kappa                        ((x0 - x0*) . d) / (d . d), d = [dr0; dv0] (eq. of Table 3)
  disp.terminal.delta_final_position_LU[i]  r_f - r_f* [LU], i = 0, 1, 2
  disp.thrust.eta_percent                   100 (T_max scale - 1)
The printed basic vectors, their scale and the cube side are parameters of these.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ogk.sil.dispersion_check import Declaration, Declared, Listed, Parameter, Uniform

if TYPE_CHECKING:
    from .cases import Case, MpspSetup

KAPPA = "initial.kappa"
TARGET = "terminal.delta_final_position_LU"
ETA = "thrust.eta_percent"


def applied_record(setup: "MpspSetup", case: "Case") -> dict[str, Any]:
    """The disp.* keys of one run's case (module doc)."""
    pert = setup.scenario.dispersions
    rec: dict[str, Any] = {"disp." + KAPPA: None, "disp." + ETA: None,
                           **{f"disp.{TARGET}[{i}]": None for i in range(3)}}
    if case.kind == "initial":
        d = np.concatenate((pert.delta_r0, pert.delta_v0))
        rec["disp." + KAPPA] = float(np.dot(case.x0[:6] - setup.problem.x0[:6], d) / np.dot(d, d))
    elif case.kind == "terminal":
        assert case.target is not None
        off = case.target[:3] - setup.problem.rf
        rec.update({f"disp.{TARGET}[{i}]": float(off[i]) for i in range(3)})
    else:
        rec["disp." + ETA] = 100.0 * (case.thrust_scale - 1.0)
    return rec


def declared(setup: "MpspSetup", table: dict[str, Any], cases: str) -> Declaration:
    """Dispersed: each kind uniform over its range on its third of the runs; paper: each listed
    case on its run (first the kappas, then the cube's vertices, then the etas)."""
    pert = setup.scenario.dispersions
    vertices = np.asarray(pert.delta_rf_vertices, dtype=np.float64)
    if cases == "paper":
        n_k, n_v = len(pert.kappa), len(vertices)
        main = (Declared(KAPPA, Listed(tuple(float(k) for k in pert.kappa), 0)),
                Declared(TARGET, Listed(tuple(tuple(float(x) for x in v) for v in vertices), n_k),
                         size=3),
                Declared(ETA, Listed(tuple(float(e) for e in pert.eta_percent), n_k + n_v)))
    else:
        main = (Declared(KAPPA, Uniform(min(pert.kappa), max(pert.kappa)), period=3, phase=0),
                Declared(TARGET, Uniform(tuple(float(x) for x in vertices.min(axis=0)),
                                         tuple(float(x) for x in vertices.max(axis=0))),
                         size=3, period=3, phase=1),
                Declared(ETA, Uniform(min(pert.eta_percent), max(pert.eta_percent)), period=3,
                         phase=2))
    basic = "Table 3's basic vector: r0 + kappa dr0, v0 + kappa dv0"
    return Declaration(table, main + (
        Declared("initial.delta_position_printed_LU", Parameter(KAPPA, basic)),
        Declared("initial.delta_velocity_printed_VU", Parameter(KAPPA, basic)),
        Declared("initial.printed_vector_scale", Parameter(KAPPA, "the ERRATUM scale of both")),
        Declared("terminal.cube_side_LU", Parameter(TARGET, "the cube the vertices span"))))
