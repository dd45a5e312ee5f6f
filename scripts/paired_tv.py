"""The meadow's default frame (950 × 720) for an earlier commit and for the working tree: the
whole frame (t_a), its volume pass (t_v) and its image-based pass (t_i), and a one-shot
`sward render`'s frame over the steady one (`one_shot`: its t_a over the profile's median),
measured alternately in one run: this machine's timings drift by ±30 % between runs, so a
speed-up is only honest as a ratio of times taken side by side.

    .venv/bin/python scripts/paired_tv.py REV [--rounds 3] [--frames 5]

REV is checked out into a temporary git worktree and run ahead of the installed tree
(PYTHONPATH) through the command line, whose `profile` and `render` keep their names and
output across commits; each round profiles the default camera's frames with each tree in a
fresh process and reports each time's median and the ratios, and how far the two trees'
frames differ (quarter-resolution FLIP, the issue's measure of "the same image"). Prints JSON.
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
from PIL import Image

ROOT = Path(__file__).resolve().parent.parent
KEYS = ("t_a_ms", "t_v_ms", "t_i_ms")
CLI = "import sys; sys.argv = ['sward'] + sys.argv[1:]; from app.cli import main; sys.exit(main())"
SCENE = ["--scene", "meadow", "--size", "950x720"]


def _sward(tree: Path, *args: str) -> None:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    subprocess.run(
        [sys.executable, "-c", CLI, *args],
        cwd=tempfile.gettempdir(),
        env=env,
        check=True,
        capture_output=True,
        text=True,
    )


def _times(tree: Path, frames: int, out: Path) -> dict[str, float]:
    """Medians of the default camera's frames (`sward profile`, its first viewpoint), and a
    one-shot `sward render`'s frame over their t_a."""
    _sward(tree, "profile", *SCENE, "--frames", str(frames), "--out", str(out))
    default = json.loads(out.read_text())["viewpoints"][0]["frames"]
    times = {k: statistics.median(f[k] for f in default) for k in KEYS}
    _sward(tree, "render", *SCENE, "--stats", str(out))
    return {**times, "one_shot": json.loads(out.read_text())["t_a_ms"] / times["t_a_ms"]}


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
            stats = Path(tmp, "stats.json")
            for _ in range(args.rounds):
                before = _times(old, args.frames, stats)
                now = _times(ROOT, args.frames, stats)
                ratios = {f"ratio_{k[:-3]}": before[k] / now[k] for k in KEYS}
                rounds.append({"before": before, "now": now, **ratios})
            images = Path(tmp, "before.png"), Path(tmp, "now.png")
            for tree, image in zip((old, ROOT), images, strict=True):
                _sward(tree, "render", *SCENE, "--out", str(image))
            flip = _flip_quarter(*(np.asarray(Image.open(p).convert("RGB")) for p in images))
        finally:
            subprocess.run(
                ["git", "-C", str(ROOT), "worktree", "remove", "--force", str(old)], check=False
            )
    medians = {
        f"median_ratio_{k[:-3]}": statistics.median(r[f"ratio_{k[:-3]}"] for r in rounds)
        for k in KEYS
    }
    for side in ("before", "now"):
        medians[f"median_one_shot_{side}"] = statistics.median(r[side]["one_shot"] for r in rounds)
    result = {"rev": args.rev, "rounds": rounds, **medians}
    print(json.dumps({**result, "flip_quarter": flip}))


def _flip_quarter(a: np.ndarray, b: np.ndarray) -> float:
    from benchmarks.references import quarter
    from core.image_diff import flip

    return float(flip(quarter(a), quarter(b))[0])


if __name__ == "__main__":
    main()
