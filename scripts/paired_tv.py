"""t_v of the meadow's default frame (950 × 720) for an earlier commit and for the working tree,
measured alternately in one run: this machine's timings drift by ±30 % between runs, so a
speed-up is only honest as a ratio of times taken side by side.

    .venv/bin/python scripts/paired_tv.py REV [--rounds 3] [--frames 5]

REV is checked out into a temporary git worktree and imported ahead of the installed tree
(PYTHONPATH); each round renders a few frames with each tree in a fresh process and reports
the medians and their ratio, and how far the two trees' frames differ (quarter-resolution
FLIP, the issue's measure of "the same image"). Prints JSON.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
PROBE = """
import json, statistics, sys
import numpy as np
from app.scenes import get_scene
from render.headless import HeadlessRenderer
doc = get_scene("meadow").document()
camera = doc.camera()
with HeadlessRenderer(doc) as renderer:
    image, _ = renderer.render(camera, (950, 720))
    times = [renderer.render(camera, (950, 720))[1].t_v_ms for _ in range(int(sys.argv[1]))]
np.save(sys.argv[2], image)
print(json.dumps(statistics.median(times)))
"""


def _t_v(tree: Path, frames: int, image: Path) -> float:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    out = subprocess.run(
        [sys.executable, "-c", PROBE, str(frames), str(image)],
        cwd=tempfile.gettempdir(),
        env=env,
        check=True,
        capture_output=True,
        text=True,
    )
    return float(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("rev")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--frames", type=int, default=5)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        old = Path(tmp, "old")
        subprocess.run(
            ["git", "-C", str(ROOT), "worktree", "add", "--detach", str(old), args.rev],
            check=True,
            capture_output=True,
        )
        try:
            rounds = []
            images = Path(tmp, "before.npy"), Path(tmp, "now.npy")
            for _ in range(args.rounds):
                before = _t_v(old, args.frames, images[0])
                now = _t_v(ROOT, args.frames, images[1])
                rounds.append({"before_ms": before, "now_ms": now, "ratio": before / now})
            flip = _flip_quarter(*(np.load(p) for p in images))
        finally:
            subprocess.run(
                ["git", "-C", str(ROOT), "worktree", "remove", "--force", str(old)], check=False
            )
    ratios = [r["ratio"] for r in rounds]
    result = {"rev": args.rev, "rounds": rounds, "median_ratio": statistics.median(ratios)}
    print(json.dumps({**result, "flip_quarter": flip}))


def _flip_quarter(a: np.ndarray, b: np.ndarray) -> float:
    from benchmarks.references import quarter
    from core.image_diff import flip

    return float(flip(quarter(a), quarter(b))[0])


if __name__ == "__main__":
    main()
