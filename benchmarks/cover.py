"""How much of the ground the volume lets through against the blades (issue: the far grass
covers the ground as its blades do): per scene, camera and density (0.3, 0.6, 1), the
ground drawn white and then black with the grass drawn as volume alone and as blades alone
(shadows off, 320 × 180), the share of ground each image row shows, and the geometric mean
over the rows where both show some ground and the blades not all of it of volume over blades
(above 1: the volume shows more ground). The views: the bench seen from 10°, 20°, 40° and 70°
above its middle, along an axis of its slices and 30° across them, and the built-in cameras
of the bench, the meadow and the patch grid; the last row the mean and the largest |ln| of
those ratios over every view and density.

Run: `sward bench --suite cover --out results.json`.
"""

from __future__ import annotations

SIZE = (320, 180)
DENSITIES = (0.3, 0.6, 1.0)
BUILT_IN = (
    ("bench", ("zones", "grazing", "default")),
    ("meadow", ("default", "path", "hill")),
    ("patch-grid", ("default", "grazing")),
)


def volume_over_blades(document, camera, size: tuple[int, int]) -> float:
    """The geometric mean over image rows of the ground the volume lets through over the
    ground the blades let through (rows where both show some and the blades not all)."""
    import numpy as np

    from benchmarks.shadows import ground_rows

    blades = ground_rows(document, camera, "geometry", size)
    volume = ground_rows(document, camera, "volume", size)
    rows = (blades > 0.02) & (volume > 0.02) & (blades < 0.95)
    return float(np.exp(np.log(volume[rows] / blades[rows]).mean())) if rows.sum() > 3 else np.nan


def _views():
    from app.scenes import get_scene
    from core.camera import Camera

    for pitch in (10.0, 20.0, 40.0, 70.0):
        for yaw in (0.0, 30.0):
            camera = Camera(target=(0.0, 0.0, 0.0), yaw=yaw, pitch=pitch, distance=8.0)
            yield "bench", f"pitch{pitch:g}_yaw{yaw:g}", camera
    for scene, names in BUILT_IN:
        document = get_scene(scene).document()
        for name in names:
            yield scene, name, document.camera(name)


def run() -> list[dict]:
    import numpy as np

    from app.scenes import get_scene

    rows, logs = [], []
    for scene, name, camera in _views():
        row: dict = {"name": f"{scene}_{name}"}
        for density in DENSITIES:
            document = get_scene(scene).document()
            document.density = density
            ratio = volume_over_blades(document, camera, SIZE)
            row[f"volume_over_blades_{density:g}"] = ratio
            if np.isfinite(ratio):
                logs.append(abs(np.log(ratio)))
        rows.append(row)
    rows.append({"name": "all", "mean_abs_ln": float(np.mean(logs)), "max_abs_ln": max(logs)})
    return rows
