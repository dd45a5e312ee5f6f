"""How live the designer is (issue: a live designer): the real window on the default meadow at
its default size, continuous redraw on, driven through the window system with xdotool — key
presses, a menu opened and closed, a camera drag, a blade-parameter edit, a paint stroke, an
undo — while frames are being drawn. Reports:

- event-handling latency: for every key and mouse event, from the X server's timestamp to the
  moment the window's thread handles it (p50 / p95 / max; goal p95 <= 50 ms, max <= 150 ms);
  and the lateness of a 10 ms timer on the window's thread (the same stall, seen without input);
- time from an input to the first frame that shows it (goal: median <= 250 ms), and to the
  first full-quality frame that shows it.

Run: `sward bench --suite latency --out results.json` (with SWARD_LATENCY_VIEW_HEIGHT=PIXELS the
meadow's LOD distances hold for a view that tall: core/lod.py). Without a display it starts Xvfb; the
window runs in a process of its own, apart from the EGL contexts of other suites. The JSON
holds each input's figures beside the summaries.
"""

from __future__ import annotations

import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TIMEOUT_S = 900


def run() -> list[dict]:
    for tool in ("xdotool",):
        if shutil.which(tool) is None:
            raise RuntimeError(f"the latency benchmark needs {tool} (apt-get install {tool})")
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "latency.json"
        env = dict(os.environ, QT_QPA_PLATFORM="xcb", SWARD_LATENCY_OUT=str(out))
        xvfb = None
        if not env.get("DISPLAY"):
            display = f":{90 + os.getpid() % 9}"
            xvfb = subprocess.Popen(
                ["Xvfb", display, "-screen", "0", "1400x900x24", "-nolisten", "tcp"],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
            env["DISPLAY"] = display
            time.sleep(1.5)
        try:
            subprocess.run(
                [sys.executable, "-m", "benchmarks.latency_session"],
                env=env,
                check=True,
                timeout=TIMEOUT_S,
            )
            session = json.loads(out.read_text())
        finally:
            if xvfb is not None:
                xvfb.terminate()
                xvfb.wait()
    return summarize(session)


def _percentiles(values: list[float]) -> dict:
    if not values:
        return {"p50_ms": float("nan"), "p95_ms": float("nan"), "max_ms": float("nan")}
    ordered = sorted(values)
    p95 = ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))]
    return {
        "p50_ms": float(statistics.median(ordered)),
        "p95_ms": float(p95),
        "max_ms": float(ordered[-1]),
        "count": float(len(ordered)),
    }


def summarize(session: dict) -> list[dict]:
    events = [e["latency_ms"] for e in session["events"]]
    timer = session["timer_late_ms"]
    first = [i["first_frame_ms"] for i in session["inputs"] if i.get("first_frame_ms") is not None]
    full = [i["full_frame_ms"] for i in session["inputs"] if i.get("full_frame_ms") is not None]
    rows = [
        {"name": "event_handling", **_percentiles(events)},
        {"name": "timer_lateness", **_percentiles(timer)},
        {
            "name": "input_to_first_frame",
            "median_ms": float(statistics.median(first)) if first else float("nan"),
            "max_ms": float(max(first)) if first else float("nan"),
        },
        {
            "name": "input_to_full_quality",
            "median_ms": float(statistics.median(full)) if full else float("nan"),
            "max_ms": float(max(full)) if full else float("nan"),
        },
    ]
    frames = session["frames"]
    full_frames = [f["t_a_ms"] for f in frames if not f["preview"]]
    rows.append(
        {
            "name": "frames",
            "count": float(len(frames)),
            "full_median_ms": float(statistics.median(full_frames)) if full_frames else 0.0,
            "inputs": [
                {k: v for k, v in i.items() if k in ("name", "first_frame_ms", "full_frame_ms")}
                for i in session["inputs"]
            ],
            "viewport": session["viewport"],
        }
    )
    return rows


if __name__ == "__main__":
    for row in run():
        print(row)
