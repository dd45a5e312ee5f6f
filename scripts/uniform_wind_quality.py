"""LOD against all-geometry (sward quality's figures) under a nearly uniform wind: one gust 200 m
across, no turbulence, so that every blade of the bench leans about alike (0.26 … 0.38 of its
length at strength 0.6). With docs/experiments/bent-capture.patch applied (the slices captured
from blades bent by a constant lean, the volume's shear switched off) it shows what slices of
bent blades would do to the wind-on agreement.

    .venv/bin/python scripts/uniform_wind_quality.py [--direction 90] [--strength 0.6]
        [--wind on] [--scene bench] [--camera zones] [--size 480x270]

Prints one JSON line: × the floor over the frame and per technique's region."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    from app.quality import QualityRun
    from app.scenes import get_scene
    from core.wind import Wind

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--direction", type=float, default=90.0)
    ap.add_argument("--strength", type=float, default=0.6)
    ap.add_argument("--wind", choices=("on", "off"), default="on")
    ap.add_argument("--scene", default="bench")
    ap.add_argument("--camera", default="zones")
    ap.add_argument("--size", default="480x270")
    args = ap.parse_args()
    try:
        size = tuple(int(v) for v in args.size.split("x"))
        wind = Wind(enabled=args.wind == "on", direction=args.direction,
                    gust_strength=args.strength, gust_scale=200.0,
                    turbulence_strength=0.0)  # fmt: skip
    except ValueError as exc:
        ap.error(str(exc))
    doc = get_scene(args.scene).document()
    doc.wind = wind
    run = QualityRun(doc, size, 1e9)
    try:
        row = run.camera_figures(args.camera, doc.camera(args.camera), None)
    finally:
        run.release()
    regions = {
        k: round(v["over_floor"], 2) for k, v in row["techniques"].items() if v.get("over_floor")
    }
    print(json.dumps({"wind": args.wind, "direction": args.direction,
                      "frame": round(row["over_floor"], 3), **regions}))  # fmt: skip


if __name__ == "__main__":
    main()
