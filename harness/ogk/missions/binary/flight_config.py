"""The binary-asteroid flight configuration as generated C (host/ogk_host/cgen.py write_c_config): the
corrector contexts' ogk_blt_config_t of a scenario's Monte Carlo nominal, one per corrector in the
flight program's slot order (port/cortex-m7/pil/blt_flight.h), so that the flight build corrects with
exactly the configuration the host campaign's cffi contexts hold (convergence_run.kernels)."""
from __future__ import annotations

from pathlib import Path

from ogk_bindings._ffi import ffi
from ogk_bindings.blt import BltConfig
from ogk_host.binary.guess import kernel_config
from ogk_host.cgen import ConfigItem, write_c_config

from . import convergence_run

#: the flight program's context slots (blt_flight.h OGK_BLT_FLIGHT_N_SLOTS), by corrector
SLOTS = ("nrpc", "lm", "hybrid")
HEADER = "ogk_blt_flight_config.h"
SYMBOL = "ogk_blt_flight_configs"


def slot_configs(nominal: convergence_run.Nominal) -> list[BltConfig]:
    """One kernel configuration per slot, as convergence_run.kernels configures the host's contexts."""
    return [kernel_config(nominal.model, nominal.layout, corrector=convergence_run.CORRECTORS[name],
                          jacobian=nominal.jacobian, tol=nominal.tol, max_iter=nominal.max_iter,
                          **nominal.fields) for name in SLOTS]


def write_flight_config(c_dir: Path, scenario_path: Path, configs: list[BltConfig],
                        transfer: str) -> Path:
    """c_dir/ogk_blt_flight_config.h: `static const ogk_blt_config_t ogk_blt_flight_configs[3]`."""
    arr = ffi.new(f"ogk_blt_config_t[{len(configs)}]")
    for i, cfg in enumerate(configs):
        arr[i] = cfg.to_c()[0]
    return write_c_config(
        ffi, [ConfigItem(SYMBOL, arr, f"the correctors {', '.join(SLOTS)} of the [monte_carlo] "
                                      f"nominal {transfer} (convergence_run.kernels)")],
        c_dir / HEADER, scenario_path, includes=("ogk/blt.h",),
        note="The BLT flight program's corrector configurations (blt_flight.h slots).")
