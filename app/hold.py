"""`sward profile --hold-ms T --path NAME`: adaptive LOD along a camera path (core/hold.py).
The path is drawn twice at the profile's size: with the shipped zones, and with the controller
turning one factor on every zone's distances to hold the full-quality frame time at T. Reported:
the frame times' median and spread, how far the median is from T, the factor frame by frame,
and popping (core/quality.py) of both sequences, drawn again at POPPING_SIZE with the factors
the controller chose, against all-geometry frames of the path (kept, render/reference_cache.py)."""

from __future__ import annotations

import json
import statistics
from pathlib import Path

import numpy as np

from app.profile import FRAME_S  # seconds of wind a frame, as `sward profile`
from core.document import Document
from core.hold import HoldFrameTime
from core.quality import popping

POPPING_SIZE = (480, 270)


def hold(
    document: Document, size: tuple[int, int], path: str, frames: int, target_ms: float, out
) -> tuple[str, dict]:
    from render.headless import HeadlessRenderer

    controller = HoldFrameTime(target_ms)
    cameras = document.path_cameras(path, frames)
    renderer = HeadlessRenderer(document)
    try:
        renderer.render(cameras[0], size, measure=True)  # shaders compile, slices convert
        shipped = [_frame(renderer, i, c, size, 1.0)[1] for i, c in enumerate(cameras)]
        held, factors = [], []
        for i, camera in enumerate(cameras):
            factors.append(controller.factor)
            ms = _frame(renderer, i, camera, size, controller.factor)[1]
            held.append(ms)
            controller.update(ms)
        pops = {
            "shipped": _popping(renderer, cameras, [1.0] * len(cameras)),
            "held": _popping(renderer, cameras, factors),
        }
    finally:
        renderer.release()
    median = statistics.median(held)
    result = {
        "scene": document.name,
        "path": path,
        "size": list(size),
        "target_ms": target_ms,
        "shipped": _spread(shipped),
        "held": _spread(held),
        "median_off_target": median / target_ms - 1.0,
        "factors": factors,
        "frame_ms": held,
        "popping": pops,
    }
    text = report(result)
    if out is not None:
        Path(out).write_text(json.dumps(result, indent=2) + "\n")
        text += f"\nwrote {out}"
    return text, result


def _frame(renderer, index: int, camera, size, factor: float) -> tuple[np.ndarray, float]:
    renderer.pipeline.time = index * FRAME_S
    renderer.pipeline.lod_scale = factor
    try:
        image, stats = renderer.render(camera, size, measure=True)
    finally:
        renderer.pipeline.lod_scale = 1.0
    return image, stats.t_a_ms


def _popping(renderer, cameras, factors) -> dict:
    """The sequence with these factors against all-geometry, at POPPING_SIZE."""
    from render.reference_cache import geometry_frame

    lod, references = [], []
    for i, (camera, factor) in enumerate(zip(cameras, factors, strict=True)):
        lod.append(_frame(renderer, i, camera, POPPING_SIZE, factor)[0])
        renderer.pipeline.time = i * FRAME_S
        references.append(geometry_frame(renderer, camera, POPPING_SIZE)[0])
    return popping(lod, references)


def _spread(times: list[float]) -> dict:
    low, high = np.percentile(times, [10, 90])
    return {"median_ms": statistics.median(times), "p10_ms": float(low), "p90_ms": float(high)}


def report(r: dict) -> str:
    s, h = r["shipped"], r["held"]
    steps = sum(1 for a, b in zip(r["factors"], r["factors"][1:], strict=False) if a != b)
    return "\n".join(
        [
            f"{r['scene']} along {r['path']} at {r['size'][0]}x{r['size'][1]}, holding "
            f"{r['target_ms']:.0f} ms a frame ({len(r['frame_ms'])} frames)",
            f"  shipped zones: median {s['median_ms']:.0f} ms (p10 {s['p10_ms']:.0f}, p90 "
            f"{s['p90_ms']:.0f}); popping {r['popping']['shipped']['popping']:.2f}",
            f"  held:          median {h['median_ms']:.0f} ms (p10 {h['p10_ms']:.0f}, p90 "
            f"{h['p90_ms']:.0f}), {r['median_off_target']:+.1%} off the target; popping "
            f"{r['popping']['held']['popping']:.2f}",
            f"  factor on every zone's distances: {r['factors'][0]:.2f} → {r['factors'][-1]:.2f} "
            f"(range {min(r['factors']):.2f} … {max(r['factors']):.2f}, changed {steps} times)",
        ]
    )
