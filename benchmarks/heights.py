"""Where along the blades the volume's rays stop against where the blades stop them: every
grass type coloured by the height along its blades (√t from its root at grey 0.1 to its tip
at white: core/patch.py's gradient), lit by white ambient light alone (no sun, blade AO,
shadows, fog), over a black ground and sky. A pixel's grey over the share of it the grass
covers is then the mean of √t where what it shows was met. Per view, the image's grassed rows
in three bands (far, middle, near), the grass-weighted mean of that over the band, drawn as
blades alone and as volume alone (320 × 180): below the blades' figure, the volume's rays
reach deeper into the grass than the blades let them, and the volume shows the darker lower
blades. The views: the bench from 10°, 40° and 70° above its middle and its `zones`, the
meadow's `default` with its own grass and with the long thin preset, and the patch grid from
10°, along its slices and 45° across them.

Run: `sward bench --suite heights --out results.json`.
"""

from __future__ import annotations

import dataclasses

SIZE = (320, 180)
ROOT = 0.1  # the roots' grey: above the black ground and sky, so grass is told from them


def _views():
    from app.scenes import get_scene
    from core.camera import Camera

    for pitch in (10.0, 40.0, 70.0):
        camera = Camera(target=(0.0, 0.0, 0.0), yaw=0.0, pitch=pitch, distance=8.0)
        yield f"bench_pitch{pitch:g}", get_scene("bench").document(), camera
    bench = get_scene("bench").document()
    yield "bench_zones", bench, bench.camera("zones")
    meadow = get_scene("meadow").document()
    yield "meadow_default", meadow, meadow.camera("default")
    from core.params import PRESETS

    thin = get_scene("meadow").document()
    thin.set_params(0, PRESETS["long thin meadow grass"])
    yield "meadow_default_long_thin", thin, thin.camera("default")
    for yaw in (0.0, 45.0):
        camera = Camera(target=(0.0, 0.0, 0.0), yaw=yaw, pitch=10.0, distance=5.0)
        yield f"patch-grid_pitch10_yaw{yaw:g}", get_scene("patch-grid").document(), camera


def _coloured_by_height(document) -> None:
    for index in range(len(document.grass_types)):
        params = document.params(index)
        document.set_params(
            index,
            params.replace(
                root_color=(ROOT,) * 3, tip_color=(1.0, 1.0, 1.0),
                blade_color_variation=0.0, vertex_light_variation=0.0,
            ),
        )  # fmt: skip
    document.light = dataclasses.replace(
        document.light, sun_color=(0.0, 0.0, 0.0), ambient_color=(1.0, 1.0, 1.0),
        sky_color=(0.0, 0.0, 0.0), blade_ao_impact=0.0, fog_distance=1e6, blade_shadows=False,
    )  # fmt: skip


def met_rows(document, camera, mode: str):
    """Per image row: the share of it the grass covers and the mean √t of what it shows there
    (0 where no grass shows)."""
    import numpy as np

    from benchmarks.shadows import ground_frames

    white, black = (frame / 255.0 for frame in ground_frames(document, camera, mode, SIZE))
    ground = (white - black).mean(axis=-1)  # how much of each pixel is ground
    sky = white.max(axis=-1) == 0.0
    grass = np.where(sky, 0.0, np.clip(1.0 - ground, 0.0, 1.0))
    grey = black.mean(axis=-1)
    share = grass.mean(axis=1)
    shown = grey.sum(axis=1) / np.maximum(grass.sum(axis=1), 1e-6)
    return share, np.where(share > 0.0, (shown - ROOT) / (1.0 - ROOT), 0.0)


def run() -> list[dict]:
    import numpy as np

    rows = []
    for name, document, camera in _views():
        _coloured_by_height(document)
        blades_share, blades = met_rows(document, camera, "geometry")
        volume_share, volume = met_rows(document, camera, "volume")
        row: dict = {"name": name}
        grassed = np.flatnonzero((blades_share > 0.05) & (volume_share > 0.05))
        for band, index in zip(("far", "middle", "near"), np.array_split(grassed, 3), strict=True):
            if index.size == 0:
                continue
            for label, share, met in (
                ("blades", blades_share, blades),
                ("volume", volume_share, volume),
            ):
                row[f"{band}_{label}"] = float(
                    (share[index] * met[index]).sum() / share[index].sum()
                )
        rows.append(row)
    return rows
