"""Live editing of a patch: a 2400-blade patch regenerated (new parameters) and converted into
2 × N vertical slices (256 × 64) and one 128² horizontal slice (thesis 4.2.1), their mips built
and uploaded (4.2.2); medians of several runs, for N = 8 (the designer's default) and 16.
Goals (issue: faster frames): regenerate + convert ≤ 150 ms for 2 × 8, ≤ 300 ms for 2 × 16.

Run: `sward bench --suite conversion --out results.json`.
"""

from __future__ import annotations

import statistics
import time

from core.params import PatchParams
from core.patch import generate_patch

GOALS_MS = {8: 150.0, 16: 300.0}


def conversion(slices: int, runs: int = 5) -> list[dict]:
    from render.context import standalone
    from render.conversion import PatchConverter
    from render.slices import SliceTextures

    ctx = standalone()
    converter = PatchConverter(ctx)
    converter.convert(generate_patch(PatchParams(blade_count=2400)), slices)  # shader JIT
    parts: dict[str, list[float]] = {"generate": [], "capture": [], "mips_upload": [], "total": []}
    for run in range(runs):
        start = time.perf_counter()
        # a new patch each run (generate_patch caches what it made)
        patch = generate_patch(PatchParams(blade_count=2400, seed=100 * slices + run + 1))
        generated = time.perf_counter()
        sliced = converter.convert(patch, slices)
        captured = time.perf_counter()
        SliceTextures.upload(ctx, sliced).release()
        ctx.finish()
        end = time.perf_counter()
        parts["generate"].append((generated - start) * 1000.0)
        parts["capture"].append((captured - generated) * 1000.0)
        parts["mips_upload"].append((end - captured) * 1000.0)
        parts["total"].append((end - start) * 1000.0)
    converter.release()
    ctx.release()
    row = {f"{k}_ms": statistics.median(v) for k, v in parts.items()}
    return [
        {
            "name": f"regenerate_convert_2400_blades_2x{slices}",
            **row,
            "goal_ms": GOALS_MS[slices],
            "runs_ms": parts["total"],
        }
    ]


def run() -> list[dict]:
    return conversion(8) + conversion(16)
