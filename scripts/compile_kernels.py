"""Compiles Sward's numba kernels into their on-disk cache (__pycache__ beside each module), once
per install: without it the first traversal or patch conversion of a fresh install, in the
designer or a test, waits ~20 s for the compiler on a 2-core machine. `make run`, `make setup`
and `make test` run it once a virtual environment (`make test` beside the linters); a kernel
whose source changed later compiles again on its first call."""

import time

import numpy as np

from core.frustum import Frustum
from core.heights import hills
from core.lod import LodConfig
from core.mipmaps import build_mips_stack, weighted_chain
from core.occupancy import DensityOccupancy
from core.params import PatchParams
from core.patch import generate_patch
from core.shadows import cover
from core.slopes import _seen
from core.terrain import Terrain
from core.tiling import mirror_bits
from core.traversal import traverse
from render.conversion import SliceLayers
from render.slices import canonical_data


def main() -> None:
    start = time.perf_counter()
    terrain = Terrain(8, 8, mirror_seed=1, heights=hills(16), height_scale=1.0)
    occupancy = DensityOccupancy(8, 8, np.ones((16, 16, 1), np.float32))
    eye = (1.0, 2.0, 1.0)
    frustum = Frustum.from_view(eye, (4.0, 0.0, 4.0), 50.0, 1.5, 0.1, 100.0)
    traverse(terrain, eye, LodConfig(), frustum, occupancy, 0)
    terrain.cells(np.arange(2), np.arange(2))
    terrain.planes_of(terrain.cells(np.arange(2), np.arange(2)))  # core/ground_planes.py
    mirror_bits(np.zeros((1, 2)))
    # the patch conversion's mip chains (hills above compiled the noise)
    build_mips_stack(np.zeros((1, 4, 4, 4), np.float32))
    build_mips_stack(np.zeros((1, 4, 4, 4), np.float32), upper_first=True)  # the slices' colour
    weighted_chain(np.zeros((1, 4, 4, 4), np.float32), np.zeros((1, 4, 4), np.float32), 3)
    canonical_data(
        SliceLayers(
            *(np.zeros((1, 4, 4, c), np.float32) for c in (4, 3)),
            *(np.zeros((1, 4, 4), np.float32) for _ in range(2)),
        )
    )
    # the slope tables' weights (core/slopes.py slope_moments), with the types it passes
    k_m = np.zeros((2, 3), np.float32)
    row = np.zeros(3, np.float32)
    through = np.ones((2, 3), np.float32)
    _seen(row[:2], k_m, k_m, k_m, row, row, through, 0.1, 1.0, k_m.copy(), k_m.copy())
    # the blades' shadow cover (core/shadows.py), with the types the renderer passes
    cover(generate_patch(PatchParams(blade_count=2)), np.array([0.5, 0.7, 0.5]), False, 2, 8)
    print(f"sward setup: numba kernels compiled in {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()
