"""Typed configuration of the kernel's energy cut-off monitor (kernel/include/ogk/cutoff.h).

    cfg = CutoffConfig(mu_m3_s2=..., target_sma_m=..., arm_before_s=..., extend_max_s=...,
                       control_period_s=...)          # ogk_cutoff_config_default, then each field
"""
from __future__ import annotations

from ogk_bindings.config import KernelConfig

__all__ = ["CutoffConfig"]


class CutoffConfig(KernelConfig):
    """ogk_cutoff_config_t: the target orbit's energy, the arm and extend windows, the step period."""

    _ctype = "ogk_cutoff_config_t"
    _default_fn = "ogk_cutoff_config_default"
