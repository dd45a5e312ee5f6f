"""Cell instances of a flat grid: the per-instance data every renderer draws from."""

from __future__ import annotations

import numpy as np

# One row per drawn patch instance: origin x, origin z (world units, one cell = 1), the local
# density that scales the patch's blade thresholds, and the LOD transition (w, side): side 0
# keeps blades with threshold / density <= w, side 1 the others (core/lod.py, thesis 5.4).
INSTANCE_DTYPE = np.dtype(
    [("origin", np.float32, 2), ("density", np.float32), ("lod", np.float32, 2)]
)


def grid_instances(nx: int, nz: int, density: float | np.ndarray = 1.0) -> np.ndarray:
    """Instances for an nx × nz grid of cells centred on the origin.

    `density` is one value for every cell or an (nx, nz) array.
    """
    if nx < 1 or nz < 1:
        raise ValueError(f"grid size must be at least 1 × 1, got {nx} × {nz}")
    ix, iz = np.meshgrid(np.arange(nx), np.arange(nz), indexing="ij")
    out = np.empty(nx * nz, dtype=INSTANCE_DTYPE)
    out["origin"][:, 0] = (ix - nx / 2.0).reshape(-1)
    out["origin"][:, 1] = (iz - nz / 2.0).reshape(-1)
    out["density"] = np.broadcast_to(np.asarray(density, dtype=np.float32), (nx, nz)).reshape(-1)
    out["lod"] = (2.0, 0.0)  # wholly inside one representation
    return out
