"""`sward profile`: frame statistics per viewpoint or along a camera path, as the thesis's
chapter 7 tables (median / min / max), written to JSON as well."""

from __future__ import annotations

import json
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
    try:
        for name, cameras in views:
            renderer.render(cameras[0], size, measure=True)  # warm-up: shaders compile lazily
            stats = [renderer.render(camera, size, measure=True)[1] for camera in cameras]
            every += stats
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
