"""Macro-cell speed-ups after the thesis's Table 7.2: the 32 × 32 cells of the `bench` scene
drawn by the volume and by the image-based renderer with macro-cells of at most 1, 2, 4, 8 and
16 cells a side, from the default camera; frame time of that technique and the speed-up over
1 × 1 cells. Medians of several frames, the sizes taking turns frame by frame.

Run: `sward bench --suite macrocells --out results.json`.
"""

from __future__ import annotations

import statistics

SIZE = (1024, 768)
SIZES = (1, 2, 4, 8, 16)
# thesis Table 7.2 (GeForce 9800 GT), ms
THESIS = {
    "volume": (22.45, 12.2, 8.65, 6.31, 6.02),
    "image": (2.24, 0.94, 0.50, 0.42, 0.41),
}


def macrocells(runs: int = 5) -> list[dict]:
    from app.scenes import get_scene
    from core.lod import LodConfig, LodLevel
    from render.headless import HeadlessRenderer

    doc = get_scene("bench").document()
    renderer = HeadlessRenderer(doc)
    camera = doc.camera()
    rows = []
    for representation, key in (("volume", "t_v_ms"), ("image", "t_i_ms")):
        configs = [LodConfig((LodLevel(representation, 0.0, None, macro=size),)) for size in SIZES]
        times: dict[int, list[float]] = {size: [] for size in SIZES}
        counts = {}
        # the sizes take turns, frame by frame: this machine's speed drifts within a run
        for frame in range(runs + 1):
            for size, config in zip(SIZES, configs, strict=True):
                doc.set_lod(0, config)
                stats = renderer.render(camera, SIZE)[1]
                if frame:  # the first round warms up
                    times[size].append(getattr(stats, key))
                    counts[size] = stats.c_v + stats.c_i
        base = statistics.median(times[SIZES[0]])
        for size, thesis_ms in zip(SIZES, THESIS[representation], strict=True):
            t = statistics.median(times[size])
            rows.append(
                {
                    "name": f"{representation}_macro_{size}",
                    "median_ms": t,
                    "speedup": base / t,
                    "instances": float(counts[size]),
                    "thesis_ms": thesis_ms,
                    "thesis_speedup": THESIS[representation][0] / thesis_ms,
                }
            )
    renderer.release()
    return rows


def run() -> list[dict]:
    return macrocells()
