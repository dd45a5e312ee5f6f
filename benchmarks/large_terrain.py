"""Terrains of 4096² cells (issue: faster frames): `sward new FILE --scene NAME --cells
4096x4096` makes the project (maps resampled to at most 1024² texels), then `sward render
--project FILE` draws its first frame in a fresh process, which is timed from its start to the
PNG written (goal ≤ 10 s) and whose peak resident memory is read back (goal ≤ 1 GB). The
meadow is the hilly one (its 1024² height map, 3 units high), the landscape the mountainous one
(80 units), the football flat.

Run: `sward bench --suite large_terrain --out results.json`.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

SCENES = ("meadow", "landscape", "football")
CELLS = "4096x4096"
SIZE = "640x360"


def _sward(*args: str) -> float:
    """Run `sward ARGS` in a fresh process; its wall time in seconds."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "app.cli", *args], check=True, capture_output=True)
    return time.perf_counter() - start


def _peak_after(run) -> tuple[float, float]:
    """Wall time and peak resident memory (MB) of the one child process `run` starts. The
    children's maximum never goes down, so each measurement runs in a process of its own."""
    probe = (
        "import resource, sys, time; from benchmarks.large_terrain import _sward; "
        "s = _sward(*sys.argv[1:]); "
        "print(s, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024)"
    )
    out = subprocess.run(
        [sys.executable, "-c", probe, *run], check=True, capture_output=True, text=True
    )
    seconds, peak = out.stdout.split()
    return float(seconds), float(peak)


def run() -> list[dict]:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in SCENES:
            project = Path(tmp, f"{scene}.sward")
            new_s = _sward("new", str(project), "--scene", scene, "--cells", CELLS)
            image = str(Path(tmp, f"{scene}.png"))
            args = ("render", "--project", str(project), "--size", SIZE, "--out", image)
            first_frame_s, peak_mb = _peak_after(args)
            rows.append(
                {
                    "name": f"{scene}_{CELLS}",
                    "new_s": new_s,
                    "first_frame_s": first_frame_s,
                    "peak_mb": peak_mb,
                    "project_mb": project.stat().st_size / 2**20,
                    "goal_s": 10.0,
                    "goal_mb": 1024.0,
                }
            )
    return rows
