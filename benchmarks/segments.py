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


def _times(renderer, camera, runs: int, modes: dict) -> tuple[dict, dict, dict]:
    """Per mode (name -> segment LOD on): its frame, its triangles and its geometry pass's
    times, the modes drawn in turns so that each sees the same machine."""
    images, triangles, times = {}, {}, {mode: [] for mode in modes}
    for mode, on in modes.items():  # warm: programs, slices, light tables
        renderer.pipeline.segment_lod = on
        images[mode], stats = renderer.render(camera, SIZE)
        triangles[mode] = stats.triangles
    for _ in range(runs):
        for mode, on in modes.items():
            renderer.pipeline.segment_lod = on
            times[mode].append(renderer.render(camera, SIZE)[1].t_g_ms)
    return images, triangles, {mode: statistics.median(t) for mode, t in times.items()}


def compare(scene_name: str, camera_name: str, runs: int = 5) -> dict:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    doc = get_scene(scene_name).document()
    camera = doc.camera(camera_name)
    renderer = HeadlessRenderer(doc)
    images, triangles, ms = _times(renderer, camera, runs, {"lod": True, "full": False})
    renderer.release()
    for index, grass in enumerate(doc.grass_types):  # every patch of one-segment blades
        doc.set_params(index, grass.params.replace(subdivisions=1))
    renderer = HeadlessRenderer(doc)
    _, _, single = _times(renderer, camera, runs, {"one": False})
    renderer.release()
    diff = Comparison.of(images["full"], images["lod"])
    return {
        "name": f"{scene_name}_{camera_name}_segments",
        "geometry_ms": ms["lod"],
        "full_segments_ms": ms["full"],
        "speedup": ms["full"] / ms["lod"] if ms["lod"] > 0 else 0.0,
        "one_segment_speedup": ms["full"] / single["one"] if single["one"] > 0 else 0.0,
        "triangles": triangles["lod"],
        "full_triangles": triangles["full"],
        "flip": diff.flip_full,
        "flip_quarter": diff.flip_quarter,
    }


def run() -> list[dict]:
    return [compare(scene, camera) for scene, camera in CASES]
