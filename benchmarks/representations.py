"""The same 1024 instances of the `bench` scene (32 × 32 flat cells) drawn with each
representation, as in the thesis's Table 7.1 (there: volume 6.45× faster than geometry, image
10× faster than volume). Medians of several frames measured with ctx.finish() around each pass.

Run: `sward bench --suite representations --out results.json`.
"""

from __future__ import annotations

import statistics

SIZE = (1024, 768)


def representations(runs: int = 3) -> list[dict]:
    from app.scenes import get_scene
    from render.context import describe
    from render.headless import HeadlessRenderer

    doc = get_scene("bench").document()
    renderer = HeadlessRenderer(doc, mode="volume")  # converts the slices once
    camera = doc.camera()
    rows = []
    for only, key in (("geometry", "t_g_ms"), ("volume", "t_v_ms"), ("image", "t_i_ms")):
        renderer.pipeline.set_mode(only)
        renderer.render(camera, SIZE)  # warm-up
        times = [getattr(renderer.render(camera, SIZE)[1], key) for _ in range(runs)]
        rows.append(
            {
                "name": f"bench_{only}_1024_instances",
                "median_ms": statistics.median(times),
                "runs_ms": times,
            }
        )
    gl = describe(renderer.ctx)
    renderer.release()
    g, v, i = (r["median_ms"] for r in rows)
    rows.append(
        {
            "name": "ratios",
            "geometry_over_volume": g / v,
            "volume_over_image": v / i,
            "thesis_geometry_over_volume": 6.45,
            "thesis_volume_over_image": 10.0,
            "gl": gl,
        }
    )
    return rows


def run() -> list[dict]:
    return representations()
