"""The guidance implementation `ogk nmpc --solver NAME` flies (and the seed campaign's `--solver`).

Its own module so that neither implementation imports the other: guidance.py (IPOPT) and
kernel_guidance.py (the flight code's ogk_nmpc) both build on guidance_base.py, and only this factory
knows both. Each is imported when asked for: the IPOPT one needs CasADi, the kernel one the compiled
bindings.
"""
from __future__ import annotations

from ogk_bindings.errors import OgkInputError
from ogk_host.rendezvous.scenario import RendezvousScenario

from . import strategy as st
from .guidance_base import Guidance

#: `--solver` names: the flight code (ogk_nmpc, C kernel) and the ground NLP (CasADi + IPOPT).
SOLVERS = ("kernel", "ipopt")


def make_guidance(name: str, scenario: RendezvousScenario, strategy: st.StrategySettings) -> Guidance:
    """The guidance implementation `--solver NAME` flies."""
    if name == "kernel":
        from .kernel_guidance import KernelGuidance   # the flight code (ogk_nmpc), through cffi
        return KernelGuidance(scenario, strategy)
    if name == "ipopt":
        from .guidance import IpoptGuidance           # the ground NLP, CasADi + IPOPT
        return IpoptGuidance(scenario, strategy)
    raise OgkInputError(f"must be one of {', '.join(SOLVERS)}, got {name!r}", key="--solver")
