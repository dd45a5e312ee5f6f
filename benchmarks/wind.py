"""What the wind costs (issue: wind): the meadow's default frame at 950 × 720 with the wind on
and off, frame by frame in turn (so that this machine's drift falls on both alike), the medians
of t_a, t_g, t_v and t_i of each and the share the wind adds. The time moves on between the
wind-on frames, as in the designer's animation. Goal on llvmpipe: ≤ 15 % added to t_a.
Trampled grass the same way: the meadow's grass laid over everywhere (a lean that turns across
the terrain, still air) against upright, the same maps drawn with and without the trample
lookup in turn.

Run: `sward bench --suite wind --out results.json`.
"""

from __future__ import annotations

import statistics

SIZE = (950, 720)
FRAMES = 5
PARTS = ("t_a_ms", "t_g_ms", "t_v_ms", "t_i_ms")


def run() -> list[dict]:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    document = get_scene("meadow").document()
    camera = document.camera()
    still = document.wind.replace(enabled=False)
    blowing = document.wind.replace(enabled=True)
    times: dict[bool, dict[str, list[float]]] = {on: {p: [] for p in PARTS} for on in (False, True)}
    with HeadlessRenderer(document) as renderer:
        renderer.render(camera, SIZE)  # slices converted, buffers made
        for frame in range(FRAMES):
            for on in (False, True):
                document.wind = blowing if on else still
                renderer.pipeline.time = 0.1 * frame
                _, stats = renderer.render(camera, SIZE, measure=True)
                for part in PARTS:
                    times[on][part].append(getattr(stats, part))
    return [_row("meadow_default_wind", times, "wind"), _trampled(get_scene, HeadlessRenderer)]


def _trampled(get_scene, renderer_class) -> dict:
    import numpy as np

    from core.trample import encode

    document = get_scene("meadow").document()
    camera = document.camera()
    w, h = document.maps.size
    turn = np.linspace(0.0, 2.0 * np.pi, w)[None, :].repeat(h, axis=0)
    document.maps.write("trample", 0, 0, encode(0.6 * np.stack([np.cos(turn), np.sin(turn)], -1)))
    times: dict[bool, dict[str, list[float]]] = {on: {p: [] for p in PARTS} for on in (False, True)}
    with renderer_class(document) as renderer:
        textures = renderer.pipeline.map_textures
        renderer.render(camera, SIZE)
        laid = textures.trample_lean
        for _ in range(FRAMES):
            for on in (False, True):
                textures.trample_lean = laid if on else 0.0  # with the trample lookup or not
                _, stats = renderer.render(camera, SIZE, measure=True)
                for part in PARTS:
                    times[on][part].append(getattr(stats, part))
    return _row("meadow_default_trampled", times, "trampled")


def _row(name: str, times: dict, label: str) -> dict:
    row: dict = {"name": name}
    for on, which in ((False, "still"), (True, label)):
        for part in PARTS:
            row[f"{which}_{part}"] = statistics.median(times[on][part])
    for part in PARTS:
        still_ms = row[f"still_{part}"]
        row[f"added_{part[:3]}_percent"] = (
            100.0 * (row[f"{label}_{part}"] - still_ms) / still_ms if still_ms > 0 else 0.0
        )
    return row
