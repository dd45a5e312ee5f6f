"""The slope tables' sums handed between the designer's render processes (render/facing.py
kept_slope_moments): both processes need the sums of every new patch, and each built them in
full, so on a CPU renderer the two shared the cores and the full frame after a blade edit (and
the first one after start) waited for both. The process that builds the sums first writes them
to a folder both processes know (SHARED_DIR_ENV, made by render/render_client.py for one
session of the designer); the other reads them there. Without the folder (a command-line
render, a test) nothing is shared.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from core.light_moments import LightMoments
from core.slopes import SlopeMoments

SHARED_DIR_ENV = "SWARD_SHARED_SUMS"
KEPT_FILES = 8  # the newest files kept in the folder


def path_for(key: str) -> Path | None:
    folder = os.environ.get(SHARED_DIR_ENV)
    return Path(folder) / f"slope-{key}.npz" if folder else None


def load(key: str) -> SlopeMoments | None:
    """The sums another process wrote under `key`, or None."""
    path = path_for(key)
    if path is None or not path.is_file():
        return None
    try:
        with np.load(path) as f:
            parts = [
                LightMoments(*(f[f"{part}_{name}"].astype(np.float64) for name in _FIELDS))
                for part in ("upright", "sheared")
            ]
            return SlopeMoments(*parts, int(f["elevations"]), int(f["azimuths"]))
    except (OSError, KeyError, ValueError):  # being replaced, or not ours: build them
        return None


def save(key: str, moments: SlopeMoments) -> None:
    """Write the sums under `key` (single precision: their tables differ by under 1e-6), then
    leave the newest KEPT_FILES in the folder."""
    path = path_for(key)
    if path is None:
        return
    arrays = {
        f"{part}_{name}": getattr(getattr(moments, part), name).astype(np.float32)
        for part in ("upright", "sheared")
        for name in _FIELDS
    }
    partial = path.with_name(f".{path.name}.{os.getpid()}")
    try:
        with open(partial, "wb") as file:
            np.savez(file, elevations=moments.elevations, azimuths=moments.azimuths, **arrays)
        os.replace(partial, path)  # the reader sees the whole file or none
        files = sorted(path.parent.glob("slope-*.npz"), key=lambda p: p.stat().st_mtime)
        for old in files[:-KEPT_FILES]:
            old.unlink(missing_ok=True)
    except OSError:  # the folder went away (the designer closing): nothing to share
        partial.unlink(missing_ok=True)


_FIELDS = ("powers", "signed", "total")
