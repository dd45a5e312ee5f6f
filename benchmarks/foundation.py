"""Patch generation time (5000 blades × 4 subdivisions) and the geometry frame time of 64
instances at 1024×768. Medians of several runs; on llvmpipe compare ratios, not absolutes.

Run: `sward bench --suite foundation --out results.json` or `python -m benchmarks.foundation`.
"""

from __future__ import annotations

import statistics
import time

from core.params import PatchParams
from core.patch import generate_patch


def patch_generation(runs: int = 7) -> dict:
    params = PatchParams(blade_count=5000, subdivisions=4)
    generate_patch(params)  # warm caches (noise map)
    times = []
    for i in range(runs):
        start = time.perf_counter()
        generate_patch(params.replace(seed=100 + i))
        times.append((time.perf_counter() - start) * 1000.0)
    return {
        "name": "patch_generation_5000x4",
        "median_ms": statistics.median(times),
        "runs_ms": times,
    }


def geometry_frame(runs: int = 5, size: tuple[int, int] = (1024, 768)) -> dict:
    from app.scenes import get_scene
    from render.context import describe
    from render.headless import HeadlessRenderer

    doc = get_scene("patch-grid").document()
    renderer = HeadlessRenderer(doc, mode="geometry")
    patch = renderer.pipeline.grass_types[0].patch
    camera = doc.camera()
    renderer.render(camera, size)  # warm up: shader JIT, buffers
    frames = [renderer.render(camera, size)[1] for _ in range(runs)]
    gl = describe(renderer.ctx)
    renderer.release()
    return {
        "name": "geometry_frame_64_instances",
        "gl": gl,
        "size": list(size),
        "instances": frames[0].c_g,
        "blades_per_patch": patch.blade_count,
        "triangles": frames[0].triangles,
        "median_t_a_ms": statistics.median(f.t_a_ms for f in frames),
        "median_t_g_ms": statistics.median(f.t_g_ms for f in frames),
        "median_t_m_ms": statistics.median(f.t_m_ms for f in frames),
        "triangles_per_second": frames[0].triangles
        / (statistics.median(f.t_g_ms for f in frames) / 1000.0),
    }


SUITE = {"patch_generation": patch_generation, "geometry_frame": geometry_frame}


def run() -> list[dict]:
    return [fn() for fn in SUITE.values()]


if __name__ == "__main__":
    import json

    print(json.dumps(run(), indent=2))
