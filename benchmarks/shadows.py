"""What the blades' shadows cost (core/shadows.py): at each camera, frames with the shadows on
and off in turn (so that this machine's drift falls on both alike), the medians of t_a, of the
shadow pass (t_s) and of the ground (t_m, which takes the far grass's share of shadow), and
the share the shadows add to t_a; and across the hand-over from the blades to the volume
(density 0.3, 480 × 270), how far the LOD frame's darkening strays from the all-geometry
frame's row by row, against two yardsticks of blade detail: the all-geometry frame a blade's
width to the side, and the same grass with two other aperiodic tilings; and how far it strays
once each of its rows is scaled to the share of ground the all-geometry frame's row shows
(what of the stray is the grass covering more or less of the ground, not the shadows); and,
for scale, how far the all-geometry frame's own rows stray from their running mean over five
rows: what a far grass that darkens each row as the blades do on average, without their
row-to-row detail, would stray by. And what the volume alone covers against the blades alone
at densities 0.3, 0.6 and 1 (shadows off): per image row the share of ground each lets through,
the geometric mean over the rows of volume over blades (above 1: the volume shows more ground).

Run: `sward bench --suite shadows --out results.json`.
"""

from __future__ import annotations

import dataclasses
import statistics

SIZE = (950, 720)
FRAMES = 5
CAMERAS = (("meadow", "default"), ("bench", "zones"), ("football", "player"))
PARTS = ("t_a_ms", "t_s_ms", "t_m_ms")


def run() -> list[dict]:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    rows = []
    for scene, name in CAMERAS:
        document = get_scene(scene).document()
        camera = document.camera(name)
        off = document.light
        on = dataclasses.replace(off, blade_shadows=True)
        times: dict[bool, dict[str, list[float]]] = {s: {p: [] for p in PARTS} for s in (0, 1)}
        with HeadlessRenderer(document) as renderer:
            for light in (off, on):  # slices converted, programs built, shadow cover measured
                document.light = light
                renderer.render(camera, SIZE)
            for _ in range(FRAMES):
                for shadows in (False, True):
                    document.light = on if shadows else off
                    _, stats = renderer.render(camera, SIZE, measure=True)
                    for part in PARTS:
                        times[shadows][part].append(getattr(stats, part))
        row: dict = {"name": f"{scene}_{name}"}
        for shadows, label in ((False, "off"), (True, "on")):
            for part in PARTS:
                row[f"{label}_{part}"] = statistics.median(times[shadows][part])
        row["added_t_a_percent"] = 100.0 * (row["on_t_a_ms"] / row["off_t_a_ms"] - 1.0)
        rows.append(row)
    hand_overs = (("bench", "zones"), ("meadow", "path"))
    return (
        rows
        + [_hand_over(scene, name) for scene, name in hand_overs]
        + [_cover(scene, name) for scene, name in hand_overs]
    )


def ground_frames(document, camera, mode: str, size: tuple[int, int]):
    """The frame with the ground drawn white and with it drawn black (shadows off), RGB as
    floats 0 … 255: their difference is how much of each pixel is ground."""
    import render.ground as ground_module
    from render.headless import HeadlessRenderer
    from render.shaders import load_program

    document.light = dataclasses.replace(document.light, blade_shadows=False)
    frames = []
    for level in (1.0, 0.0):
        ground_module.load_program = _ground_loader(level)
        try:
            with HeadlessRenderer(document, mode=mode) as renderer:
                frames.append(renderer.render(camera, size, measure=False)[0].astype(float))
        finally:
            ground_module.load_program = load_program
    return frames[0], frames[1]


def ground_rows(document, camera, mode: str, size: tuple[int, int]):
    """Per image row, the share of the ground it shows (ground_frames' difference over
    white)."""
    import numpy as np

    white, black = ground_frames(document, camera, mode, size)
    return np.asarray(((white - black) / 255.0).mean(axis=(1, 2)))


def _cover(scene: str, name: str) -> dict:
    """The volume alone against the blades alone: per density, the geometric mean over the
    rows where both show some ground and the blades not all of it of the ratio of the ground
    each lets through."""
    from app.scenes import get_scene
    from benchmarks.cover import volume_over_blades

    row: dict = {"name": f"{scene}_{name}_cover"}
    for density in (0.3, 0.6, 1.0):
        document = get_scene(scene).document()
        document.density = density
        ratio = volume_over_blades(document, document.camera(name), (480, 270))
        row[f"volume_over_blades_{density:g}"] = ratio
    return row


def _hand_over(scene: str, name: str) -> dict:
    import numpy as np

    from app.quality import shifted
    from app.scenes import get_scene
    from core.quality import technique_regions
    from render.grass_type import technique_colors
    from render.headless import HeadlessRenderer

    size = (480, 270)
    document = get_scene(scene).document()
    document.density = 0.3
    camera = document.camera(name)

    def rows(mode: str, cam, regions: bool = False):
        """Per image row, how much darker the shadows make it; with `regions` the rows'
        shares of geometry and volume too."""
        with HeadlessRenderer(document, mode=mode) as renderer:
            frames = []
            for shadows in (False, True):
                document.light = dataclasses.replace(document.light, blade_shadows=shadows)
                frames.append(renderer.render(cam, size, measure=False)[0].astype(float))
            dark = (frames[0] - frames[1]).mean(axis=(1, 2))
            if not regions:
                return dark
            renderer.pipeline.view = "techniques"
            techniques = renderer.render(cam, size, measure=False)[0]
        found = technique_regions(frames[1].astype(np.uint8), techniques, technique_colors())
        return dark, found["geometry"].mean(axis=1), found["volume"].mean(axis=1)

    lod, blades, volume = rows("lod", camera, regions=True)
    first = int(np.flatnonzero(blades > 0.2)[0])  # the hand-over: 30 rows either side
    band = np.arange(max(first - 30, 0), min(first + 30, size[1]))
    geometry = rows("geometry", camera)
    # the LOD frame's rows as if each showed as much ground as the all-geometry frame's
    lod_ground = ground_rows(document, camera, "lod", size)
    geometry_ground = ground_rows(document, camera, "geometry", size)
    same_ground = lod * np.where(
        lod_ground > 0.01, geometry_ground / np.maximum(lod_ground, 0.01), 1.0
    )
    side = rows("geometry", shifted(camera, float(document.params(0).width_max)))
    tilings = []
    for seed in (11, 12):
        document.terrain_spec = dataclasses.replace(document.terrain_spec, mirror_seed=seed)
        tilings.append(rows("geometry", camera))

    def strays(a, b) -> float:
        return float(np.abs(a - b)[band].mean())

    k = 5  # rows: each row's darkening the mean of the rows around it
    smoothed = np.convolve(np.pad(geometry, k // 2, mode="edge"), np.ones(k) / k, "valid")

    return {
        "name": f"{scene}_{name}_hand_over",
        "rows_lod": strays(lod, geometry),
        "rows_lod_same_ground": strays(same_ground, geometry),
        "rows_shifted": strays(side, geometry),
        "rows_tilings": max(strays(tilings[0], geometry), strays(tilings[1], geometry)),
        "rows_smoothed": strays(smoothed, geometry),
        "volume_side": float(lod[band[volume[band] > 0.5]].mean()),
        "volume_side_geometry": float(geometry[band[volume[band] > 0.5]].mean()),
        "blades_side": float(lod[band[blades[band] > 0.2]].mean()),
        "blades_side_geometry": float(geometry[band[blades[band] > 0.2]].mean()),
    }


def _ground_loader(level: float):
    """load_program for render/ground.py whose ground is drawn in one grey `level`, the
    uniforms it reads kept (the ground's own colour mixed in at a hundred-thousandth)."""
    from render.shaders import ShaderError, stage_source

    made: dict = {}
    line = "f_color = vec4(soil(v_world, u_eye, inside, sun), 1.0);"
    flat = f"f_color = vec4(mix(soil(v_world, u_eye, inside, sun), vec3({level}), 0.99999), 1.0);"

    def program(ctx, file, defines=()):
        key = (ctx, file, tuple(defines))
        if key not in made:
            fragment = stage_source(file, "FRAGMENT_SHADER", tuple(defines))
            if line not in fragment:
                raise ShaderError(f"shaders/{file}: no ground colour to replace")
            made[key] = ctx.program(
                vertex_shader=stage_source(file, "VERTEX_SHADER", tuple(defines)),
                fragment_shader=fragment.replace(line, flat),
            )
        return made[key]

    return program
