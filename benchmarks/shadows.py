"""What the blades' shadows cost (core/shadows.py): at each camera, frames with the shadows on
and off in turn (so that this machine's drift falls on both alike), the medians of t_a, of the
shadow pass (t_s) and of the ground (t_m, which takes the far grass's share of shadow), and
the share the shadows add to t_a.

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
    return rows
