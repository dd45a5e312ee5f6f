"""Conversion time of a 2400-blade patch into 2 × 16 vertical slices (256 × 64) and one 128²
horizontal slice (thesis 4.2.1), median of several runs.

Run: `sward bench --suite conversion --out results.json`.
"""

from __future__ import annotations

import statistics
import time

from core.params import PatchParams
from core.patch import generate_patch


def conversion(runs: int = 3) -> dict:
    from render.context import standalone
    from render.conversion import PatchConverter

    ctx = standalone()
    converter = PatchConverter(ctx)
    patch = generate_patch(PatchParams(blade_count=2400))
    converter.convert(patch, 16)  # warm up: shader JIT
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        converter.convert(patch, 16)
        times.append((time.perf_counter() - start) * 1000.0)
    converter.release()
    ctx.release()
    return {
        "name": "conversion_2400_blades_2x16",
        "median_ms": statistics.median(times),
        "runs_ms": times,
    }


def run() -> list[dict]:
    return [conversion()]
