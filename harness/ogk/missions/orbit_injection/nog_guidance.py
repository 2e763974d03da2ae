"""The kernel's VTD-NOG (kernel/include/ogk/nog.h) as the SIL loop's guidance, all runs at once.

One ogk_nog_t per run, one shared read-only ogk_nog_table_t decoded from the flight bundle
(`ogk tables leo-geo`, regenerated when the scenario changes). The C batch loops in
csrc/nog_batch.c cross from Python once per sampling or command time for all runs.
A run whose guidance returns an error status at a sample is flagged failed (the kernel still
serves its safe command, which the loop flies until the run is counted).
"""
from __future__ import annotations

import dataclasses
import hashlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario
from ogk_bindings.errors import TableError
from ogk_host.orbit_injection import derive
from ogk_host.orbit_injection import tables as ground_tables

from ogk_bindings._ffi import PRECISION, ffi, lib
from ogk_bindings.kernel import KernelError
from ogk_bindings.nog import NogConfig

from .csrc_batch import lib as batch
from .guidance import GuidanceSetup

F64 = NDArray[np.float64]
BoolArray = NDArray[np.bool_]



@dataclasses.dataclass(frozen=True)
class NogTables:
    """The tables a campaign flies, checked against its scenario (provenance in the JSON)."""

    directory: Path
    bundle: Path
    manifest: dict[str, Any]
    sha256: dict[str, str]          #: file name -> SHA-256 of every table file flown

    @property
    def t_f_star_s(self) -> float:
        return float(self.manifest["t_f_s"])


def prepare_tables(scn: OrbitInjectionScenario, table_dir: Path | None = None) -> NogTables:
    """The scenario's own tables: generated into its directory under build/tables when missing,
    otherwise checked (manifest names this scenario's SHA-256, files intact). A user's directory
    (`table_dir`) is only checked, never written over (TableError, one line)."""
    if scn.path is None:
        raise TableError("the scenario has no file: tables are keyed by the scenario file")
    # the tables of the kernel's precision (F64 or F32, each in its own default directory)
    directory = ground_tables.ensure_nog_tables(scn.path, table_dir, precision=PRECISION)
    manifest = ground_tables.check_tables(directory, scn.path, precision=PRECISION)
    bundle = Path(directory) / ground_tables.BUNDLE_FILE
    sha = {p.name: hashlib.sha256(p.read_bytes()).hexdigest()
           for p in sorted(Path(directory).glob("*.ogkt"))}
    return NogTables(Path(directory), bundle, manifest, sha)


def load_table(bundle: Path) -> object:
    """Decodes and validates a bundle into a new ogk_nog_table_t (raises KernelError)."""
    table = ffi.new("ogk_nog_table_t *")
    data = bundle.read_bytes()
    status = lib.ogk_nog_table_load(table, ffi.from_buffer("uint8_t[]", data), len(data))
    if status != lib.OGK_OK:
        raise KernelError(status, "ogk_nog_table_load")
    return table


def nog_config(scn: OrbitInjectionScenario, table: Any, last_interval_s: float | None = None
               ) -> NogConfig:
    """ogk_nog_config_t from the scenario's guidance block (the end-game bounds included), bound
    to `table` (kept alive by the config). `scn` is resolved (derive.resolve) where it was loaded;
    `last_interval_s`: the sampling interval at the end of the burn, which sets the terminating
    sample of eq. (32) (default: the scenario's Delta t_S, sampled throughout)."""
    derive.require_resolved(scn)
    t_f_star_s = float(table.t_f_star_s)
    return NogConfig(table=table,
                     sample_interval_s=(scn.sample_interval_s if last_interval_s is None
                                        else last_interval_s),
                     dtf_max_s=scn.end_game.dtf_max_s, du_max_rad=scn.end_game.du_max_rad,
                     tau_freeze=derive.effective_settings(scn).tau_freeze(t_f_star_s))


class KernelNogGuidance:
    """Guidance protocol of ogk.missions.orbit_injection.guidance, flown by the kernel's ogk_nog_* functions."""

    name = "nog"

    def __init__(self, setup: GuidanceSetup, bundle: Path) -> None:
        n = setup.n_runs
        self._table = load_table(bundle)
        self._cfg = nog_config(setup.scenario, self._table, setup.last_interval_s)
        self._ctx = ffi.new("ogk_nog_t[]", n)
        status = np.zeros(n, dtype=np.int32)
        rc = batch.ogk_sil_nog_init_batch(self._ctx, n, self._cfg.to_c(),
                                        ffi.from_buffer("int32_t[]", status, require_writable=True))
        if rc != lib.OGK_OK:
            raise KernelError(rc, "ogk_nog_init")
        self._n = n
        self._cutoff = np.full(n, np.inf)
        self._t_f = np.full(n, float(self._table.t_f_star_s))
        self._tau = np.zeros(n)
        self._flags = np.zeros(n, dtype=np.uint32)
        self._status = np.zeros(n, dtype=np.int32)
        self._failed = np.zeros(n, dtype=bool)
        self._terminating = np.zeros(n, dtype=bool)
        self.flag_history: list[NDArray[np.uint32]] = []

    @classmethod
    def for_tables(cls, tables: NogTables) -> Callable[[GuidanceSetup], "KernelNogGuidance"]:
        """A guidance factory flying `tables` (checked by prepare_tables)."""
        def factory(setup: GuidanceSetup) -> KernelNogGuidance:
            return cls(setup, tables.bundle)
        factory.name = cls.name  # type: ignore[attr-defined]
        return factory

    @property
    def t_f_star_s(self) -> float:
        return float(self._table.t_f_star_s)

    def sample(self, t: F64, nav: F64, due: BoolArray | None = None) -> None:
        """Samples the runs `due` (default all) at t (N,) with nav (N, 6)."""
        t = np.ascontiguousarray(t, dtype=np.float64)
        nav = np.ascontiguousarray(nav, dtype=np.float64)
        # Runs already cut off (t frozen at their cut-off) are left alone.
        take = (t < self._cutoff) & ~self._terminating
        if due is not None:
            take &= due
        active = np.ascontiguousarray(take, dtype=np.uint8)
        batch.ogk_sil_nog_sample_batch(
            self._ctx, self._n, ffi.from_buffer("uint8_t[]", active),
            ffi.from_buffer("double[]", t), ffi.from_buffer("double[]", nav),
            ffi.from_buffer("double[]", self._cutoff, require_writable=True),
            ffi.from_buffer("double[]", self._t_f, require_writable=True),
            ffi.from_buffer("double[]", self._tau, require_writable=True),
            ffi.from_buffer("uint32_t[]", self._flags, require_writable=True),
            ffi.from_buffer("int32_t[]", self._status, require_writable=True))
        was = active.astype(bool)
        self._failed |= was & (self._status != lib.OGK_OK)
        # Eq. (32): the interval in which tau reaches 1 is the last; its cut-off time is final.
        self._terminating |= was & ((self._flags & lib.OGK_NOG_FLAG_TERMINATING) != 0)
        self.flag_history.append(np.where(was, self._flags, 0).astype(np.uint32))

    def command(self, t: F64) -> tuple[F64, F64]:
        t = np.ascontiguousarray(np.broadcast_to(t, (self._n,)), dtype=np.float64)
        alpha = np.empty(self._n)
        beta = np.empty(self._n)
        flags = np.empty(self._n, dtype=np.uint32)
        status = np.empty(self._n, dtype=np.int32)
        batch.ogk_sil_nog_command_batch(
            self._ctx, self._n, ffi.from_buffer("double[]", t),
            ffi.from_buffer("double[]", alpha, require_writable=True),
            ffi.from_buffer("double[]", beta, require_writable=True),
            ffi.from_buffer("uint32_t[]", flags, require_writable=True),
            ffi.from_buffer("int32_t[]", status, require_writable=True))
        return alpha, beta

    def cutoff_time(self) -> F64:
        """Predicted cut-off per run, t_k + (1 - tau_k) t_f^(k); final once the terminating
        sample (eq. 32) is taken."""
        return self._cutoff.copy()

    def failed(self) -> BoolArray:
        return self._failed.copy()

    def flight_time(self) -> F64:
        """t_f^(k) in force per run [s]."""
        return self._t_f.copy()
