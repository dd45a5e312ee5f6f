"""LOD frame against the geometry-only frame at the same camera and image size (DESIGN.md:
"LOD frame against geometry-only frame"): the bench scene's `zones` camera, and with
SWARD_BENCH_HEAVY=1 the football `player` camera (its geometry-only frame draws the 134,622
visible cells' 5000 blades each, 2.7 G triangles: more than 25 minutes on llvmpipe, a GPU run).

Run: `sward bench --suite lod_speedup --out results.json`.
"""

from __future__ import annotations

import os
import statistics

SIZE = (1024, 768)


def speedup(scene_name: str, camera_name: str, runs: int = 2) -> dict:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    doc = get_scene(scene_name).document()
    renderer = HeadlessRenderer(doc)
    camera = doc.camera(camera_name)
    out = {}
    for mode in ("lod", "geometry"):
        renderer.pipeline.set_mode(mode)
        renderer.render(camera, SIZE)
        out[mode] = statistics.median(renderer.render(camera, SIZE)[1].t_a_ms for _ in range(runs))
    renderer.release()
    return {
        "name": f"{scene_name}_{camera_name}_lod_vs_geometry",
        "lod_ms": out["lod"],
        "geometry_only_ms": out["geometry"],
        "speedup": out["geometry"] / out["lod"],
    }


def run() -> list[dict]:
    rows = [speedup("bench", "zones")]
    if os.environ.get("SWARD_BENCH_HEAVY") == "1":
        rows.append(speedup("football", "player", runs=1))
    return rows
