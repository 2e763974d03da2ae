"""Typed configuration of the kernel's terminal steering along the velocity to be gained
(kernel/include/ogk/terminal.h).

    cfg = TerminalConfig(mu_m3_s2=..., target_radius_m=..., window_s=..., shape_gain=..., ...)
"""
from __future__ import annotations

from ogk_bindings.config import KernelConfig

__all__ = ["TerminalConfig"]


class TerminalConfig(KernelConfig):
    """ogk_terminal_config_t: the circular target orbit, the window, the shaping and the turn limit."""

    _ctype = "ogk_terminal_config_t"
    _default_fn = "ogk_terminal_config_default"
