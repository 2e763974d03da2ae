"""PNG figures of every family (matplotlib, Agg backend): the set-up (`pyplot`, `save`) and the
final-error dispersion figure every mission's campaign can draw."""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray


def pyplot() -> Any:
    """matplotlib.pyplot on the Agg backend (PNG files, no display): every family's figures."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig: Any, path: Path, dpi: int = 110, tight: bool = False) -> Path:
    """Writes and closes the figure (`tight`: the bounding box cut to the drawing)."""
    plt = pyplot()
    fig.savefig(path, dpi=dpi, **({"bbox_inches": "tight"} if tight else {}))
    plt.close(fig)
    return path


def dispersion_figure(errors: Mapping[str, NDArray[np.float64]], ok: NDArray[np.bool_],
                      pairs: Sequence[tuple[str, str]], labels: Mapping[str, str],
                      hist_key: str, hist_line: float | None, title: str,
                      tolerances: Mapping[str, float] | None = None) -> Any:
    """Scatter plots of final-error pairs over the successful runs, a histogram of one quantity,
    and the acceptance box (dashed) where both quantities of a pair have a tolerance."""
    plt = pyplot()
    n_panels = len(pairs) + 1
    cols = 2
    rows = (n_panels + 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(10, 4 * rows))
    flat = np.ravel(axes)
    for ax, (kx, ky) in zip(flat, pairs):
        ax.scatter(errors[kx][ok], errors[ky][ok], s=6, alpha=0.6)
        if tolerances and kx in tolerances and ky in tolerances:
            tx, ty = tolerances[kx], tolerances[ky]
            ax.plot([-tx, tx, tx, -tx, -tx], [-ty, -ty, ty, ty, -ty], "r--", lw=0.8,
                    label="acceptance")
        ax.set_xlabel(labels.get(kx, kx))
        ax.set_ylabel(labels.get(ky, ky))
        ax.grid(alpha=0.3)
    ax = flat[len(pairs)]
    ax.hist(errors[hist_key][ok], bins=min(40, max(5, int(ok.sum() ** 0.5))))
    if hist_line is not None:
        ax.axvline(hist_line, color="k", ls="--", label="nominal")
        ax.legend()
    ax.set_xlabel(labels.get(hist_key, hist_key))
    for extra in flat[n_panels:]:
        extra.set_visible(False)
    fig.suptitle(title)
    fig.tight_layout()
    return fig
