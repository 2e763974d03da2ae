"""Plain-text tables for people and JSON helpers for machines, shared by every mission's report."""
from __future__ import annotations

import math
from typing import Any

import numpy as np


def fmt(v: float | None) -> str:
    """A number in a table cell: '-' for missing, 4 decimals or scientific outside [1e-2, 1e4)."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    if v == 0.0:
        return "0"
    if abs(v) >= 1e4 or abs(v) < 1e-2:
        return f"{v:.3e}"
    return f"{v:.4f}"


def table(header: list[str], rows: list[list[str]]) -> list[str]:
    """Aligned columns: the first left-aligned, the others right-aligned, a rule under the header."""
    widths = [max(len(r[i]) for r in [header] + rows) for i in range(len(header))]

    def line(cells: list[str]) -> str:
        return "  ".join(c.ljust(w) if i == 0 else c.rjust(w)
                         for i, (c, w) in enumerate(zip(cells, widths)))
    head = line(header)
    return [head, "-" * len(head), *(line(r) for r in rows)]


def is_finite_number(v: Any) -> bool:
    """A record value that is a finite number (a bool, a string, None, NaN or inf is not)."""
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) \
        and math.isfinite(float(v))


def finite_or_none(obj: Any) -> Any:
    """NaN/inf -> None, recursively (JSON has no NaN)."""
    if isinstance(obj, float):
        return obj if np.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: finite_or_none(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [finite_or_none(v) for v in obj]
    return obj
