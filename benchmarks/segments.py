"""Blade segments fewer with distance (core/segments.py) and each cell's run of blades
(render/geometry.py): the geometry pass as drawn against every blade of every cell drawn with
all its segments, at the same camera and size, and the picture they make against each other
(FLIP at full and at quarter resolution). For scale, the pass with every patch made of
one-segment blades, every blade drawn: what fewer segments alone can save at most here; and
the pass as drawn with a fragment stage that reads and computes nothing: what the blades'
positions, set-up and rasterising under 4× MSAA cost on this renderer, and so the most that
cheaper fragment shading could save. A row per larger tolerance (the LOD dock's setting, up to
its 8 px) gives what trading the picture for fewer segments buys.

Run: `sward bench --suite segments --out results.json`.
"""

from __future__ import annotations

import statistics
from dataclasses import replace

from core.quality import Comparison

SIZE = (960, 540)
TOLERANCES_PX = (1.0, 2.0, 4.0, 8.0)
CASES = (("bench", "zones"), ("football", "player"), ("meadow", "default"), ("meadow", "path"))


# a fragment stage that reads none of the blade's inputs (the uniforms the renderer sets kept):
# llvmpipe runs a discarded fragment to its end, so a discard first would keep the shader's
# whole cost; this leaves the vertex stage's position, the triangles' set-up and rasterising
_FLOOR = "    f_color = vec4(u_alpha_ref) + texture(u_blade, vec2(0.5));\n"


def _set(renderer, mode: str) -> None:
    """Segment LOD and the runs of blades on (`lod`, `floor`), or every blade with all its
    segments; `floor`: a fragment stage that computes nothing."""
    import render.geometry as geometry
    from benchmarks.volume_cost import floor_loader
    from render.shaders import load_program

    on = mode != "full" and mode != "one"
    renderer.pipeline.segment_lod = on
    geometry.load_program = floor_loader(_FLOOR, whole=True) if mode == "floor" else load_program
    for grass in renderer.pipeline.grass_types:
        grass.geometry.spans = geometry.GeometryRenderer.spans if on else 1


def _times(renderer, camera, runs: int, modes: tuple, apply=_set) -> tuple[dict, dict, dict]:
    """Per mode (set by `apply`): its frame, its triangles and its geometry pass's times, the
    modes drawn in turns so that each sees the same machine."""
    images, triangles, times = {}, {}, {mode: [] for mode in modes}
    try:
        for mode in modes:  # warm: programs, slices, light tables
            apply(renderer, mode)
            images[mode], stats = renderer.render(camera, SIZE)
            triangles[mode] = stats.triangles
        for _ in range(runs):
            for mode in modes:
                apply(renderer, mode)
                times[mode].append(renderer.render(camera, SIZE)[1].t_g_ms)
    finally:
        _set(renderer, "lod")
    return images, triangles, {mode: statistics.median(t) for mode, t in times.items()}


def _tolerance(renderer, mode) -> None:
    """Every blade with all its segments (`full`), or segment LOD within `mode` pixels."""
    _set(renderer, "full" if mode == "full" else "lod")
    if mode != "full":
        for grass in renderer.pipeline.grass_types:
            grass.lod = replace(grass.lod, segment_tolerance=mode)


def tolerances(scene_name: str, camera_name: str, runs: int = 5) -> list[dict]:
    """The geometry pass with segment LOD at each of TOLERANCES_PX against every blade with
    all its segments, timed in turns with it, and the picture against it."""
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    doc = get_scene(scene_name).document()
    camera = doc.camera(camera_name)
    renderer = HeadlessRenderer(doc)
    modes = ("full", *TOLERANCES_PX)
    images, triangles, ms = _times(renderer, camera, runs, modes, _tolerance)
    renderer.release()
    return [
        {
            "name": f"{scene_name}_{camera_name}_within_{px:g}px",
            "speedup": ms["full"] / ms[px],
            "triangles": triangles[px],
            "full_triangles": triangles["full"],
            "flip_quarter": Comparison.of(images["full"], images[px]).flip_quarter,
        }
        for px in TOLERANCES_PX
    ]


def compare(scene_name: str, camera_name: str, runs: int = 5) -> dict:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    doc = get_scene(scene_name).document()
    camera = doc.camera(camera_name)
    renderer = HeadlessRenderer(doc)
    images, triangles, ms = _times(renderer, camera, runs, ("lod", "full", "floor"))
    renderer.release()
    for index, grass in enumerate(doc.grass_types):  # every patch of one-segment blades
        doc.set_params(index, grass.params.replace(subdivisions=1))
    renderer = HeadlessRenderer(doc)
    _, _, single = _times(renderer, camera, runs, ("one",))
    renderer.release()
    diff = Comparison.of(images["full"], images["lod"])
    return {
        "name": f"{scene_name}_{camera_name}_segments",
        "geometry_ms": ms["lod"],
        "full_segments_ms": ms["full"],
        "speedup": ms["full"] / ms["lod"] if ms["lod"] > 0 else 0.0,
        "one_segment_speedup": ms["full"] / single["one"] if single["one"] > 0 else 0.0,
        "fragment_floor_speedup": ms["full"] / ms["floor"] if ms["floor"] > 0 else 0.0,
        "triangles": triangles["lod"],
        "full_triangles": triangles["full"],
        "flip": diff.flip_full,
        "flip_quarter": diff.flip_quarter,
    }


def run() -> list[dict]:
    rows = []
    for scene, camera in CASES:
        rows += [compare(scene, camera), *tolerances(scene, camera)]
    return rows
