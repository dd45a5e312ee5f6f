"""`sward profile`: frame statistics per viewpoint or along a camera path, as the thesis's
chapter 7 tables (median / min / max), written to JSON as well. While the project's wind blows
the frames follow it (FRAME_S of wind a frame), and the same frames are drawn again with the
wind off: what the wind costs, per technique."""

from __future__ import annotations

import json
import statistics
from pathlib import Path

from core.document import Document
from core.profile import (
    SUM_ALLOWANCE_MS,
    SUM_TOLERANCE,
    frames_csv,
    parts_add_up,
    summarize,
    table,
)
from core.stats import FrameStats

FRAME_S = 1.0 / 30.0  # seconds of wind from one profiled frame to the next
PARTS = ("t_a_ms", "t_g_ms", "t_v_ms", "t_i_ms")


def profile(
    document: Document,
    size: tuple[int, int],
    frames: int,
    path: str | None,
    out: Path | None,
    only: str | None = None,
) -> tuple[str, dict]:
    """Render and measure; return the printed table and the JSON document."""
    from render.headless import HeadlessRenderer

    renderer = HeadlessRenderer(document, mode=only or "lod")
    if path is not None:
        views = [(f"path {path}", document.path_cameras(path, frames))]
    else:
        views = [(name, [document.camera(name)] * frames) for name in document.cameras]
    rows, result = [], {"scene": document.name, "size": list(size), "viewpoints": []}
    every = []
    wind = document.wind
    costs = []
    try:
        for name, cameras in views:
            renderer.render(cameras[0], size, measure=True)  # warm-up: shaders compile lazily
            stats = _frames(renderer, cameras, size)
            every += stats
            if wind.enabled:
                document.wind = wind.replace(enabled=False)
                try:
                    costs.append((name, _wind_cost(stats, _frames(renderer, cameras, size))))
                finally:
                    document.wind = wind
            summary = summarize(stats)
            rows.append((name, summary))
            result["viewpoints"].append(
                {
                    "name": name,
                    "summary": summary,
                    "parts_add_up": all(parts_add_up(s) for s in stats),
                    "frames": [s.to_dict() for s in stats],
                }
            )
    finally:
        renderer.release()
    text = table(rows)
    if costs:
        result["wind_cost"] = {name: cost for name, cost in costs}
        for name, cost in costs:
            added = ", ".join(f"{p[:3]} {cost[p]['added_percent']:+.1f} %" for p in PARTS)
            text += f"\nwind at {name}: {added} (medians against the same frames, wind off)"
    ok = all(v["parts_add_up"] for v in result["viewpoints"])
    result["parts_add_up"] = ok
    text += (
        f"\nparts t_q + t_u + t_g + t_v + t_i + t_m + t_o (clear, resolve) "
        f"{'add up to' if ok else 'DO NOT add up to'} t_a within "
        f"{SUM_TOLERANCE:.0%} + {SUM_ALLOWANCE_MS:g} ms in every frame"
    )
    if out is not None and out.suffix.lower() == ".csv":  # the designer's recordings too
        out.write_text(frames_csv(every))
        text += f"\nwrote {out}"
    elif out is not None:
        out.write_text(json.dumps(result, indent=2) + "\n")
        text += f"\nwrote {out}"
    return text, result


def _frames(renderer, cameras, size) -> list[FrameStats]:
    """One measured frame a camera, each FRAME_S of wind after the one before."""
    out = []
    for index, camera in enumerate(cameras):
        renderer.pipeline.time = index * FRAME_S
        out.append(renderer.render(camera, size, measure=True)[1])
    return out


def _wind_cost(blowing: list[FrameStats], still: list[FrameStats]) -> dict:
    """Per part, the medians with and without the wind and the share the wind adds."""
    cost = {}
    for part in PARTS:
        on = statistics.median(getattr(s, part) for s in blowing)
        off = statistics.median(getattr(s, part) for s in still)
        added = 100.0 * (on - off) / off if off > 0 else 0.0
        cost[part] = {"wind": on, "still": off, "added_percent": added}
    return cost
