"""How live the designer is (issue: every edit live): the real window on the default meadow at
its default size, continuous redraw on, driven through the window system with xdotool while
frames are being drawn (benchmarks/latency_session.py): the technique view, a camera drag, a
typed blade count, a preset, the slice count, the sun's elevation, an LOD zone's distance, a
wind preset and a paint stroke, each REPS times, every edit followed by its undo and redo.
Reports:

- per input, the time from it to the first frame that shows it and to the first full-quality
  frame that shows it: median and max over its repetitions (goals: first <= 150 ms median,
  <= 250 ms max; full <= 1.0 s median);
- the time from the designer's start to its first full frame (goal <= 5 s), and the frames
  shown per second while the wind blows (goal >= 5, drafts count);
- event-handling latency: for every key and mouse event, from the X server's timestamp to the
  moment the window's thread handles it (p50 / p95 / max), and the lateness of a 10 ms timer
  on the window's thread.

Run: `sward bench --suite latency --out results.json` (SWARD_LATENCY_ONLY="blade count typed,wind"
sends only the inputs named; with SWARD_LATENCY_VIEW_HEIGHT=PIXELS the
meadow's LOD distances hold for a view that tall: core/lod.py). Without a display it starts
Xvfb; the window runs in a process of its own, apart from the EGL contexts of other suites. The
JSON holds each input's figures beside the summaries.
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

TIMEOUT_S = 1800


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
            env["SWARD_LATENCY_LAUNCHED_MS"] = str(time.monotonic() * 1000.0)
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
    if session.get("error"):
        print(f"latency session: the driver stopped: {session['error']}", file=sys.stderr)
    rows = [
        {"name": "event_handling", **_percentiles([e["latency_ms"] for e in session["events"]])},
        {"name": "timer_lateness", **_percentiles(session["timer_late_ms"])},
        {"name": "startup_to_full_frame", "ms": float(session["startup_ms"])},
    ]
    by_name: dict[str, list[dict]] = {}
    for entry in session["inputs"]:
        by_name.setdefault(entry["name"], []).append(entry)
    for name, entries in by_name.items():
        first = [e["first_frame_ms"] for e in entries if e.get("first_frame_ms") is not None]
        full = [e["full_frame_ms"] for e in entries if e.get("full_frame_ms") is not None]
        rows.append(
            {
                "name": name,
                "first_median_ms": _median(first),
                "first_max_ms": max(first) if first else float("nan"),
                "full_median_ms": _median(full),
                "full_max_ms": max(full) if full else float("nan"),
                "shown": float(len(full)),
                "sent": float(len(entries)),
            }
        )
    wind = session.get("wind") or {}
    rows.append({"name": "wind_frames_per_second", "fps": float(wind.get("fps", float("nan")))})
    full_frames = [f["t_a_ms"] for f in session["frames"] if not f["draft"]]
    rows.append(
        {
            "name": "frames",
            "count": float(len(session["frames"])),
            "full_median_ms": _median(full_frames),
            "viewport": session["viewport"],
            "inputs": [
                {k: e.get(k) for k in ("name", "effect_ms", "first_frame_ms", "full_frame_ms")}
                | {"missed": bool(e.get("missed"))}
                for e in session["inputs"]
            ],
        }
    )
    return rows


def _median(values: list[float]) -> float:
    return float(statistics.median(values)) if values else float("nan")


if __name__ == "__main__":
    for row in run():
        print(row)
