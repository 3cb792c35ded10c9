"""One drawing function per paper figure, reading netCDF outputs only.

Each ``draw_<label>`` takes opened :class:`xarray.Dataset` objects (and the
figure's options from config.yaml) and returns a matplotlib Figure;
:func:`save_figure` writes it as ``<stem>.pdf`` and ``<stem>.png``.
Modules: :mod:`.maps` (traj3, traj2), :mod:`.homoclinic` (bcsc),
:mod:`.travelling` (plot4-5, plotcomplin).
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PNG_DPI = 150


def save_figure(fig, stem) -> list[Path]:
    """Save ``fig`` as ``stem.pdf`` and ``stem.png`` with fixed metadata.

    No creation date is written, so rebuilding a figure from the same data
    gives the same files.
    """
    stem = Path(stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    out = []
    for ext, meta in (("pdf", {"CreationDate": None, "ModDate": None}), ("png", {"Software": None})):
        path = stem.with_suffix(f".{ext}")
        fig.savefig(path, dpi=PNG_DPI, metadata=meta)
        out.append(path)
    plt.close(fig)
    return out


def figure(nrows=1, ncols=1, width=6.4, height=3.6, **kw):
    """A new figure with the project's layout defaults."""
    return plt.subplots(nrows, ncols, figsize=(width, height), constrained_layout=True, **kw)
