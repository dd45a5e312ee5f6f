"""Conversion time of a 2400-blade patch into 2 × N vertical slices (256 × 64) and one 128²
horizontal slice (thesis 4.2.1), and the time to build the slice mips and upload them (4.2.2),
medians of several runs, for N = 16 (the issue's number) and 8 (the designer's default).

Run: `sward bench --suite conversion --out results.json`.
"""

from __future__ import annotations

import statistics
import time

from core.params import PatchParams
from core.patch import generate_patch


def conversion(slices: int, runs: int = 3) -> list[dict]:
    from render.context import standalone
    from render.conversion import PatchConverter
    from render.slices import SliceTextures

    ctx = standalone()
    converter = PatchConverter(ctx)
    patch = generate_patch(PatchParams(blade_count=2400))
    converter.convert(patch, slices)  # warm up: shader JIT
    render_ms, upload_ms = [], []
    for _ in range(runs):
        start = time.perf_counter()
        sliced = converter.convert(patch, slices)
        mid = time.perf_counter()
        SliceTextures.upload(ctx, sliced).release()
        ctx.finish()
        end = time.perf_counter()
        render_ms.append((mid - start) * 1000.0)
        upload_ms.append((end - mid) * 1000.0)
    converter.release()
    ctx.release()
    return [
        {
            "name": f"conversion_2400_blades_2x{slices}",
            "median_ms": statistics.median(render_ms),
            "runs_ms": render_ms,
        },
        {
            "name": f"slice_mips_upload_2x{slices}",
            "median_ms": statistics.median(upload_ms),
            "runs_ms": upload_ms,
        },
    ]


def run() -> list[dict]:
    return conversion(16) + conversion(8)
