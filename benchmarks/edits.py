"""What an edit costs the next frame, headless (the render process's own path, without the
window): the default scene (meadow, default camera, 950 × 720) drawn once, then edited and drawn
again, several times per kind of edit, against the frame that follows no edit. A light edit
should cost no more than a steady frame: the far representations' tables keep the light apart
from the blades (core/light_moments.py). A blade edit regenerates and converts the patch.

The designer answers an edit with a draft (half resolution) and then the full frame: the suite
also times a blade edit's draft against a steady draft, and the full frame after it.

Run: `sward bench --suite edits --out results.json` (medians and maxima, ms; compare the ratio
to the steady frame, not the times).
"""

from __future__ import annotations

import dataclasses
import statistics
import time

SIZE = (950, 720)
RUNS = 5


def run() -> list[dict]:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    doc = get_scene("meadow").document()
    camera = doc.camera()
    renderer = HeadlessRenderer(doc)

    def frame(draft: bool = False) -> float:
        start = time.perf_counter()
        renderer.render(camera, SIZE, measure=False, half_resolution=draft)
        return (time.perf_counter() - start) * 1000.0

    def sun(k: int) -> None:
        doc.light = dataclasses.replace(doc.light, sun_elevation=40.0 + 3.0 * k)

    def blades(k: int) -> None:
        params = doc.grass_types[0].params
        doc.set_params(0, params.replace(length_min=params.length_min * (1.04 if k % 2 else 0.96)))

    def wind_sun(k: int) -> None:
        doc.wind = doc.wind.replace(enabled=True)
        sun(k + RUNS)

    edits = {"none": lambda k: None, "sun elevation": sun, "blade length": blades,
             "sun elevation, wind on": wind_sun}  # fmt: skip
    frame()  # warm-up: the patch's sums, the slices, the compiled kernels
    rows = []
    steady = None
    for name, edit in edits.items():
        if name == "sun elevation, wind on":
            edit(-1)
            frame()  # the wind's first frame builds the bent sums
        times = []
        for k in range(RUNS):
            edit(k)
            times.append(frame())
        median = statistics.median(times)
        steady = median if name == "none" else steady
        rows.append(
            {
                "name": f"meadow_{name.replace(', ', '_').replace(' ', '_')}",
                "median_ms": median,
                "max_ms": max(times),
                "over_steady": median / steady if steady else 1.0,
            }
        )
    # the designer answers an edit with a draft first (half resolution), then the full frame
    drafts, steady_drafts, fulls = [], [], []
    doc.wind = doc.wind.replace(enabled=False)
    frame(draft=True)
    for k in range(RUNS):
        steady_drafts.append(frame(draft=True))
        blades(k)
        drafts.append(frame(draft=True))
        fulls.append(frame())
    steady_draft = statistics.median(steady_drafts)
    for name, times, against in (
        ("meadow_none_draft", steady_drafts, steady_draft),
        ("meadow_blade_length_draft", drafts, steady_draft),
        ("meadow_blade_length_full_after_draft", fulls, steady),
    ):
        median = statistics.median(times)
        rows.append(
            {
                "name": name,
                "median_ms": median,
                "max_ms": max(times),
                "over_steady": median / against,
            }
        )
    renderer.release()
    return rows
