"""Typed configuration of the kernel's VTD-NOG guidance (kernel/include/ogk/nog.h, docs/design/vtd-nog.md).

    cfg = NogConfig(table=table, sample_interval_s=2.0, dtf_max_s=..., du_max_rad=..., tau_freeze=...)
    cfg.to_c()                          # the ogk_nog_config_t * that ogk_nog_init takes

Starts from ogk_nog_config_default (the defaults live in C) and sets any field by its C name. The
kernel reads the table (or view) in place without copying it: the configuration keeps it alive
(ogk_bindings.config).
"""
from __future__ import annotations

from ogk_bindings.config import KernelConfig

__all__ = ["NogConfig"]


class NogConfig(KernelConfig):
    """ogk_nog_config_t: the bound table (or view), Delta t_S and the end-game guard."""

    _ctype = "ogk_nog_config_t"
    _default_fn = "ogk_nog_config_default"
