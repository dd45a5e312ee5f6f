"""Cell instances of a flat grid: the per-instance data every renderer draws from."""

from __future__ import annotations

import numpy as np

from core.tiling import mirror_bits

# One row per drawn patch instance (the thesis's cell data structure, 6.2 and 6.4):
# - origin: x, z of the cell's corner (world units, one cell = 1);
# - density: a local scale of the patch's blade thresholds;
# - lod: the LOD transition (w, side): side 0 keeps blades with threshold / density <= w, side 1
#   the others (core/lod.py, thesis 5.4);
# - size: the (macro-)cell's extent in cells along x and z (volume and image-based repeat their
#   slices; macro-cells at a terrain's edge may be rectangular, thesis 6.2);
# - mirror: the aperiodic tiling's symmetry vector (s_x, s_z) in {-1, 1} (core/tiling.py);
# - config: the config transform into design-map texture space, uv = config.xy + local ·
#   config.zw for a point `local` in cell units from the origin (thesis 6.4, configTf);
# - ground: the lowest ground height in the (macro-)cell and its unplanarity, highest − lowest
#   (thesis 6.4.4, eq. 6.14: the volume cuboid is extruded over that range).
INSTANCE_DTYPE = np.dtype(
    [
        ("origin", np.float32, 2),
        ("density", np.float32),
        ("lod", np.float32, 2),
        ("size", np.float32, 2),
        ("mirror", np.float32, 2),
        ("config", np.float32, 4),
        ("ground", np.float32, 2),
    ]
)


def grid_instances(
    nx: int,
    nz: int,
    density: float | np.ndarray = 1.0,
    mirror_seed: int | None = None,
) -> np.ndarray:
    """Instances for an nx × nz grid of cells centred on the origin.

    `density` is one value for every cell or an (nx, nz) array. With `mirror_seed` the cells are
    mirrored by the aperiodic tiling; without it none is. The design maps span the whole grid.
    """
    if nx < 1 or nz < 1:
        raise ValueError(f"grid size must be at least 1 × 1, got {nx} × {nz}")
    ix, iz = np.meshgrid(np.arange(nx), np.arange(nz), indexing="ij")
    out = np.zeros(nx * nz, dtype=INSTANCE_DTYPE)
    out["origin"][:, 0] = (ix - nx / 2.0).reshape(-1)
    out["origin"][:, 1] = (iz - nz / 2.0).reshape(-1)
    out["density"] = np.broadcast_to(np.asarray(density, dtype=np.float32), (nx, nz)).reshape(-1)
    out["lod"] = (2.0, 0.0)  # wholly inside one representation
    out["size"] = 1.0
    out["mirror"] = 1.0 if mirror_seed is None else mirror_bits(out["origin"], mirror_seed)
    out["config"][:, 0] = ix.reshape(-1) / nx
    out["config"][:, 1] = iz.reshape(-1) / nz
    out["config"][:, 2] = 1.0 / nx
    out["config"][:, 3] = 1.0 / nz
    return out
