"""How much brighter or darker the blades turn under a uniform lean, against the volume, seen
from one elevation and distance at several azimuths: the bench's grass with its own shading
(colours, AO, light), a nearly uniform wind (gusts 200 m across, strength 0.6: a lean of about
0.3), each representation drawn alone (`--only`) at 160 × 90, the green channel's mean over a
window around the target, wind on over still.

    .venv/bin/python scripts/wind_ratio_table.py [--direction 0] [--azimuths 135,180,225]
        [--elevation 6] [--distance 12]

Azimuth 0 puts the camera at -z looking towards +z (as scripts/facing_check.py). Prints one JSON
line: per azimuth the blades' ratio, the volume's, and the blades' over the volume's, which is
what the volume would have to be multiplied by to follow the blades."""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

SIZE = (160, 90)
WINDOW = (slice(40, 55), slice(40, 120))


def main() -> None:
    from app.scenes import CameraSpec, get_scene
    from core.wind import Wind
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--direction", type=float, default=0.0, help="the wind's, degrees")
    ap.add_argument("--azimuths", default="135,180,225")
    ap.add_argument("--elevation", type=float, default=6.0)
    ap.add_argument("--distance", type=float, default=12.0)
    args = ap.parse_args()
    try:
        azimuths = [float(v) for v in args.azimuths.split(",")]
    except ValueError:
        ap.error(f"--azimuths {args.azimuths}: give degrees separated by commas")
    scene = dataclasses.replace(get_scene("bench"), mirror_seed=None)
    ctx = standalone()
    el = math.radians(args.elevation)
    level = args.distance * math.cos(el)
    rows = []
    for azimuth in azimuths:
        az = math.radians(azimuth)
        eye = (level * math.sin(az), args.distance * math.sin(el), -level * math.cos(az))
        placed = dataclasses.replace(scene, cameras={"default": CameraSpec(eye, (0, 0, 0), 300.0)})
        doc = placed.document()
        camera = doc.camera("default")
        means = {}
        for mode in ("geometry", "volume"):
            for on in (False, True):
                doc.wind = Wind(enabled=on, direction=args.direction, gust_strength=0.6,
                                gust_scale=200.0, turbulence_strength=0.0)  # fmt: skip
                with HeadlessRenderer(doc, ctx, mode=mode) as renderer:
                    image = renderer.render(camera, SIZE, measure=False)[0]
                means[mode, on] = float(image[WINDOW][..., 1].astype(np.float64).mean())
        blades = means["geometry", True] / means["geometry", False]
        volume = means["volume", True] / means["volume", False]
        rows.append({"azimuth": azimuth, "blades": round(blades, 3), "volume": round(volume, 3),
                     "ratio": round(blades / volume, 3)})  # fmt: skip
    print(json.dumps({"direction": args.direction, "elevation": args.elevation,
                      "distance": args.distance, "views": rows}))  # fmt: skip


if __name__ == "__main__":
    main()
