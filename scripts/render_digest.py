"""Render every built-in scene from every named camera through the command line, and compare two
such runs image by image: the check that a change of the code's structure left every rendered
image and every instance count as it was.

    python scripts/render_digest.py render DIR [--size WxH]
    python scripts/render_digest.py compare DIR_BEFORE DIR_AFTER

`render` runs `python -m app.cli` (so PYTHONPATH chooses the tree being checked): for each scene
and camera the LOD frame shaded and in technique colours, each single representation for the
small scenes, and a project file written with `sward new` and rendered back. `compare` prints the
largest pixel difference and any changed instance count per image, and exits 1 if any differ.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
from PIL import Image

COUNTS = ("c_g", "c_v", "c_i", "blades", "triangles")
SINGLE = ("patch-grid", "meadow", "bench")


def _cli(*args: str) -> str:
    run = subprocess.run(
        [sys.executable, "-m", "app.cli", *args], capture_output=True, text=True, check=False
    )
    if run.returncode:
        raise SystemExit(f"sward {' '.join(args)} failed: {run.stderr.strip()}")
    return run.stdout


def scenes() -> dict[str, list[str]]:
    """Scene name -> camera names, as `sward scenes` lists them."""
    found: dict[str, list[str]] = {}
    name = None
    for line in _cli("scenes").splitlines():
        if line and not line.startswith(" "):
            name = line.split()[0]
        match = re.match(r"\s+cameras: (.*) \(default", line)
        if match and name:
            found[name] = match.group(1).split(", ")
    return found


def render(folder: Path, size: str) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    jobs = []
    for scene, cameras in scenes().items():
        for camera in cameras:
            base = ["--scene", scene, "--camera", camera, "--size", size]
            jobs.append((f"{scene}-{camera}", base))
            jobs.append((f"{scene}-{camera}-techniques", [*base, "--view", "techniques"]))
        if scene in SINGLE:
            for only in ("geometry", "volume", "image"):
                jobs.append((f"{scene}-{only}", ["--scene", scene, "--size", size, "--only", only]))
    project = folder / "meadow.sward"
    _cli("new", str(project), "--scene", "meadow")
    jobs.append(("project-meadow", ["--project", str(project), "--size", size]))
    for name, args in jobs:
        _cli(
            "render",
            *args,
            "--out",
            str(folder / f"{name}.png"),
            "--stats",
            str(folder / f"{name}.json"),
        )
        print(name, flush=True)


def compare(before: Path, after: Path) -> int:
    failed = 0
    for png in sorted(before.glob("*.png")):
        other = after / png.name
        if not other.exists():
            print(f"{png.stem}: missing after")
            failed += 1
            continue
        a = np.asarray(Image.open(png), np.int16)
        b = np.asarray(Image.open(other), np.int16)
        diff = int(np.abs(a - b).max()) if a.shape == b.shape else -1
        sa = json.loads(png.with_suffix(".json").read_text())
        sb = json.loads(other.with_suffix(".json").read_text())
        counts = [f"{k} {sa[k]}->{sb[k]}" for k in COUNTS if sa.get(k) != sb.get(k)]
        bad = diff != 0 or counts
        failed += bool(bad)
        print(
            f"{png.stem}: max pixel difference {diff}{'; ' + ', '.join(counts) if counts else ''}"
        )
    print(f"{failed} of {len(list(before.glob('*.png')))} images differ")
    return 1 if failed else 0


def main(argv: list[str]) -> int:
    if len(argv) >= 2 and argv[0] == "render":
        size = argv[argv.index("--size") + 1] if "--size" in argv else "200x150"
        render(Path(argv[1]), size)
        return 0
    if len(argv) == 3 and argv[0] == "compare":
        return compare(Path(argv[1]), Path(argv[2]))
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
