"""Typed kernel configurations with a pointer field (ogk_bindings.config.KernelConfig): the
configuration keeps the object its pointer field points to alive (the kernel reads a NOG table in
place, cffi frees an owning cdata nothing references), through `replace` as well; the end-game
configurations (NogConfig, CutoffConfig, TerminalConfig) start from the kernel's own defaults."""
from __future__ import annotations

import gc
import weakref

import pytest

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.cutoff import CutoffConfig
from ogk_bindings.nog import NogConfig
from ogk_bindings.terminal import TerminalConfig

pytestmark = pytest.mark.req("OGK-HAR-010")


def test_a_pointer_field_keeps_what_it_points_to_alive() -> None:
    table = ffi.new("ogk_nog_table_t *")
    table.t_f_star_s = 105.8
    alive = weakref.ref(table)
    cfg = NogConfig(table=table, sample_interval_s=1.0)
    del table
    gc.collect()
    assert alive() is not None and cfg.table.t_f_star_s == 105.8
    again = cfg.replace(sample_interval_s=0.5)
    del cfg
    gc.collect()
    assert alive() is not None and again.table.t_f_star_s == 105.8
    assert again.sample_interval_s == 0.5
    unbound = again.replace(table=None)
    del again
    gc.collect()
    assert alive() is None and unbound.table == ffi.NULL


@pytest.mark.parametrize("cls", [NogConfig, CutoffConfig, TerminalConfig])
def test_a_configuration_starts_from_the_kernels_defaults(cls: type) -> None:
    c = ffi.new(f"{cls._ctype} *")
    assert getattr(lib, cls._default_fn)(c) == lib.OGK_OK
    assert bytes(ffi.buffer(cls().to_c())) == bytes(ffi.buffer(c))
