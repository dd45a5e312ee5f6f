"""Brush stroke latency (issue: map painting): the time from a mouse move to the updated
texture for a 64-texel and a 512-texel brush on a 2048 × 2048 map — one dab painted into the
colour map, and the dirty rectangle written to the GL texture array. Goal: under 5 ms of CPU
for the 64-texel brush. Medians of many moves along a stroke.

Run: `sward bench --suite brush --out results.json`.
"""

from __future__ import annotations

import statistics
import time


def brush(moves: int = 60) -> list[dict]:
    from core.brush import Brush, Stroke
    from core.design_maps import DesignMaps
    from render.context import standalone
    from render.design_maps import DesignMapTextures

    ctx = standalone()
    maps = DesignMaps(2048)
    mirror = DesignMapTextures(ctx, maps)
    rows = []
    for size in (64, 512):
        # one dab per move: moves a spacing apart
        b = Brush(size=size, strength=0.5, value=(0.9, 0.8, 0.2, 0.8), spacing=0.25)
        stroke = Stroke(maps, "color", b)
        step = size * b.spacing
        total = []
        x = 100.0
        for i in range(moves):
            x += step
            y = 1024.0 + 200.0 * ((i % 20) / 20.0)
            start = time.perf_counter()
            stroke.add(x % 2000, y)
            mirror.flush()
            ctx.finish()
            total.append((time.perf_counter() - start) * 1000.0)
        stroke.undo()
        row = {
            "name": f"brush_{size}px_on_2048",
            "median_ms": statistics.median(total),
            "max_ms": max(total),
        }
        if size == 64:
            row["goal_ms"] = 5.0
        rows.append(row)
    mirror.release()
    ctx.release()
    return rows


def run() -> list[dict]:
    return brush()
