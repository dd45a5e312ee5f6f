"""Brush stroke latency (issue: map painting): the time from a mouse move to the updated
texture for a 64-texel and a 512-texel brush on a 2048 × 2048 map — the ground under the cursor
picked on a hilly 64 × 64-cell terrain (core/picking.py), one dab painted into the colour map,
and the dirty rectangle written to the GL texture array. Goal: under 5 ms of CPU for the
64-texel brush. Medians of many moves along a stroke.

Run: `sward bench --suite brush --out results.json`.
"""

from __future__ import annotations

import statistics
import time


def brush(moves: int = 60) -> list[dict]:
    from core.brush import Brush, Stroke
    from core.camera import Camera
    from core.design_maps import DesignMaps
    from core.heights import hills
    from core.picking import ground_hit, pixel_ray, world_to_texel
    from core.terrain import Terrain
    from render.context import standalone
    from render.design_maps import DesignMapTextures

    ctx = standalone()
    maps = DesignMaps(2048)
    mirror = DesignMapTextures(ctx, maps)
    terrain = Terrain.centred(64, 64, heights=hills(2048, seed=7), height_scale=3.0)
    camera = Camera.from_eye_target((0.0, 14.0, 30.0), (0.0, 0.0, 0.0))
    rows = []
    for size in (64, 512):
        # one dab per move: moves a spacing apart
        b = Brush(size=size, strength=0.5, value=(0.9, 0.8, 0.2, 0.8), spacing=0.25)
        stroke = Stroke(maps, "color", b)
        total, painting = [], []
        for i in range(moves):
            # the cursor sweeps across the view; each move lands about a spacing further
            px = 200.0 + 600.0 * i / moves
            py = 300.0 + 40.0 * ((i % 20) / 20.0)
            dabs = stroke.dabs
            start = time.perf_counter()
            hit = ground_hit(terrain, *pixel_ray(camera, px, py, 1024, 768))
            if hit is not None:
                stroke.add(*world_to_texel(terrain, maps.size, hit[0], hit[2]))
            mirror.flush()
            ctx.finish()
            total.append((time.perf_counter() - start) * 1000.0)
            if stroke.dabs > dabs:
                painting.append(total[-1])
        stroke.undo()
        row = {
            "name": f"brush_{size}px_on_2048",
            "median_ms": statistics.median(total),
            "max_ms": max(total),
            "median_ms_moves_that_painted": statistics.median(painting),
            "dabs_per_move": round(stroke.dabs / moves, 2),
        }
        if size == 64:
            row["goal_ms"] = 5.0
        rows.append(row)
    mirror.release()
    ctx.release()
    return rows


def run() -> list[dict]:
    return brush()
