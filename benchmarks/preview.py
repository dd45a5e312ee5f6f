"""The designer's interactive frames: the default scene (meadow, default camera, 950 × 720 —
the viewport of a 1200 × 760 window) drawn at full quality and at half resolution without
multisampling, and the instances the
bare-cell skipping saves. Medians of several frames; compare the ratio, not the times. The full
frame is also compared with its stored reference (quarter-resolution FLIP): the volume pass's
speed-ups were meant to keep the picture.

Run: `sward bench --suite preview --out results.json`.
"""

from __future__ import annotations

import statistics

SIZE = (950, 720)
# the frame as it was before the volume pass was made faster (tests/render/references.py)
REFERENCE = "meadow-default-lod-950x720"


def preview(runs: int = 3) -> list[dict]:
    from app.scenes import get_scene
    from benchmarks import references
    from render.headless import HeadlessRenderer

    doc = get_scene("meadow").document()
    renderer = HeadlessRenderer(doc)
    camera = doc.camera()
    rows = []
    times = {}
    for skip in (True, False):
        renderer.pipeline.skip_bare_cells = skip
        for half in (False, True):
            renderer.render(camera, SIZE, half_resolution=half)  # warm-up
            frames = [renderer.render(camera, SIZE, half_resolution=half)[1] for _ in range(runs)]
            name = f"meadow_{'half' if half else 'full'}{'' if skip else '_no_skip'}"
            times[name] = statistics.median(f.t_a_ms for f in frames)
            last = frames[-1]
            row = {
                "name": name,
                "median_ms": times[name],
                "t_v_ms": statistics.median(f.t_v_ms for f in frames),
                "instances": last.c_g + last.c_v + last.c_i,
            }
            if skip and not half:  # the frame the stored reference holds
                image, _ = renderer.render(camera, SIZE, measure=False)
                row["flip_quarter_vs_reference"] = references.moved(
                    references.by_name(REFERENCE), image
                )
            rows.append(row)
    rows.append(
        {
            "name": "preview_speedup",
            "ratio": times["meadow_full"] / times["meadow_half"],
            "skip_speedup_full": times["meadow_full_no_skip"] / times["meadow_full"],
        }
    )
    renderer.release()
    return rows


def run() -> list[dict]:
    return preview()
