"""Blade segments fewer with distance (core/segments.py): the geometry pass with segment LOD
against every blade drawn with all its segments, at the same camera and size, and the picture
they make against each other (FLIP at full and at quarter resolution). For scale, the pass
with every patch made of one-segment blades: what fewer segments can save at most on this
renderer.

Run: `sward bench --suite segments --out results.json`.
"""

from __future__ import annotations

import statistics

from core.quality import Comparison

SIZE = (960, 540)
CASES = (("bench", "zones"), ("football", "player"), ("meadow", "default"), ("meadow", "path"))


def compare(scene_name: str, camera_name: str, runs: int = 5) -> dict:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    doc = get_scene(scene_name).document()
    renderer = HeadlessRenderer(doc)
    camera = doc.camera(camera_name)
    modes = ("lod", "full", "one segment")
    original = [grass.params for grass in doc.grass_types]
    times: dict[str, list[float]] = {mode: [] for mode in modes}
    images, triangles = {}, {}

    def draw(mode: str):
        renderer.pipeline.segment_lod = mode != "full"
        for index, grass in enumerate(doc.grass_types):  # one segment: the patch made so
            whole = original[index].subdivisions
            doc.set_params(
                index, grass.params.replace(subdivisions=1 if mode == "one segment" else whole)
            )
        return renderer.render(camera, SIZE)

    for mode in modes:  # warm them all: programs, slices, light tables
        images[mode], stats = draw(mode)
        triangles[mode] = stats.triangles
    for _ in range(runs):  # in turns, so each sees the same machine
        for mode in modes:
            times[mode].append(draw(mode)[1].t_g_ms)
    renderer.release()
    diff = Comparison.of(images["full"], images["lod"])
    lod, full, one = (statistics.median(times[mode]) for mode in modes)
    return {
        "name": f"{scene_name}_{camera_name}_segments",
        "geometry_ms": lod,
        "full_segments_ms": full,
        "speedup": full / lod if lod > 0 else 0.0,
        "one_segment_speedup": full / one if one > 0 else 0.0,
        "triangles": triangles["lod"],
        "full_triangles": triangles["full"],
        "flip": diff.flip_full,
        "flip_quarter": diff.flip_quarter,
    }


def run() -> list[dict]:
    return [compare(scene, camera) for scene, camera in CASES]
