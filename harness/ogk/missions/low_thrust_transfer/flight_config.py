"""Flight configuration of an MPSP low-thrust-transfer scenario as const C
(docs/guides/flight-integration.md): the kernel config and nominal weights `ogk cases` flies."""
from __future__ import annotations

from pathlib import Path


def write_flight_config(out: Path, scenario: Path | None, setup: object | None = None) -> list[Path]:
    """The header of `setup` (default: build_setup of `scenario`, on the scenario's own nominal)."""
    import numpy as np

    from ogk_host.cgen import ConfigItem, write_c_config

    from ogk_bindings._ffi import ffi
    from .cases import build_setup, default_scenario_path

    if setup is None:
        setup = build_setup(scenario_path=scenario)
    cfg = setup.guidance.cfg.to_c()
    nw = setup.guidance.n_weights
    weights = ffi.new(f"double[{nw}]", [float(w) for w in np.asarray(setup.guidance.cfg.weights_nom)])
    path = write_c_config(
        ffi, [ConfigItem("ogk_flight_mpsp_config", cfg,
                         f"MPSP (ogk/mpsp.h), basis {setup.basis}, order {setup.order}: ogk_mpsp_init"),
              ConfigItem("ogk_flight_mpsp_weights_nom", weights,
                         "nominal Fourier weights epsilon_0 (eq. 50), = the config's weights_nom[0..n)")],
        out / "c" / "ogk_mpsp_flight_config.h",
        scenario if scenario is not None else default_scenario_path(), includes=("ogk/mpsp.h",),
        defines={"OGK_FLIGHT_MPSP_N_WEIGHTS": nw, "OGK_FLIGHT_MPSP_N_SEG_NOM": setup.guidance.n_seg_nom,
                 "OGK_FLIGHT_MPSP_LAMBDA_M0_NOM": float(cfg.lambda_m0_nom)},
        note=f"Normalised units (LU = {setup.lu_km:.17g} km, MU = {setup.mu_kg:.17g} kg); "
             "n_seg_nom = 0: counted by ogk_mpsp_init. Nominal: "
             f"{setup.nominal_path.name if setup.nominal_path else '?'} (SHA-256 {setup.nominal_sha256}).")
    return [path]
