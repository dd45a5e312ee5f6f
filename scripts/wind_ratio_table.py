"""How much brighter or darker the blades turn under a uniform lean, against the volume, by
the view's elevation and azimuth: a flat grid of the bench's grass (or `--grass SCENE:INDEX`, that
scene's grass type, light and wind) with its own shading, a nearly uniform wind along the
scene's heading (gusts 200 m across, strength 0.6: a lean of about 0.3), each representation
drawn alone (`--only`) at 160 × 90 from an eye `--eye-height` over the ground, the green
channel's mean over a window around the target, wind on over still.

    .venv/bin/python scripts/wind_ratio_table.py [--direction D] [--grass meadow:1]
        [--elevations 5,10,15,25] [--azimuths 0,45,90,135,180,225,270,315] [--cells 16]

Azimuth 0 puts the camera at -z looking towards +z (as scripts/facing_check.py). Prints one JSON
line: per elevation and azimuth the blades' ratio, the volume's, and the blades' over the
volume's ("ratio"), the table docs/experiments/wind-light-table.patch reads."""

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
WINDOW = (slice(38, 52), slice(40, 120))  # around the target, at the frame's centre


def main() -> None:
    from app.scenes import get_scene
    from core.camera import Camera
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--direction", type=float, help="the wind's, degrees (default: the scene's)")
    ap.add_argument("--azimuths", default="0,45,90,135,180,225,270,315")
    ap.add_argument("--elevations", default="5,10,15,25")
    ap.add_argument("--eye-height", type=float, default=2.0, help="over the ground, world units")
    ap.add_argument("--strength", type=float, default=0.6, help="gust strength (lean about half)")
    ap.add_argument("--cells", type=int, default=16, help="a flat grid of N × N of the bench")
    ap.add_argument(
        "--grass", default=None,
        help="SCENE:INDEX: that scene's grass type (and light, wind) on the flat grid instead",
    )  # fmt: skip
    args = ap.parse_args()
    try:
        azimuths = [float(v) for v in args.azimuths.split(",")]
        elevations = [float(v) for v in args.elevations.split(",")]
    except ValueError:
        ap.error("--azimuths / --elevations: give degrees separated by commas")
    scene = dataclasses.replace(
        get_scene("bench").resized(args.cells, args.cells), mirror_seed=None
    )
    doc = scene.document()
    if args.grass:
        name, _, index = args.grass.partition(":")
        source = get_scene(name).document()
        grass = source.grass_types[int(index or 0)]
        doc.set_params(0, grass.params)
        doc.set_lod(0, grass.lod)
        doc.light = source.light
        doc.wind = source.wind
    wind = doc.wind.replace(enabled=True, gust_strength=args.strength, gust_scale=200.0,
                            turbulence_strength=0.0, blade_reach=1.0)  # fmt: skip
    if args.direction is not None:
        wind = wind.replace(direction=args.direction)
    ctx = standalone()
    renderers = {mode: HeadlessRenderer(doc, ctx, mode=mode) for mode in ("geometry", "volume")}
    table: dict[str, list] = {"blades": [], "volume": [], "ratio": []}
    try:
        for elevation in elevations:
            el = math.radians(elevation)
            distance = args.eye_height / math.sin(el)
            level = distance * math.cos(el)
            rows: dict[str, list] = {k: [] for k in table}
            for azimuth in azimuths:
                az = math.radians(azimuth)
                eye = (level * math.sin(az), args.eye_height, -level * math.cos(az))
                camera = Camera.from_eye_target(eye, (0.0, 0.0, 0.0), fov_y=50.0)
                means = {}
                for on in (False, True):
                    doc.wind = wind.replace(enabled=on)
                    for mode, renderer in renderers.items():
                        image = renderer.render(camera, SIZE, measure=False)[0][WINDOW]
                        means[mode, on] = float(image[..., 1].astype(np.float64).mean())
                blades = means["geometry", True] / means["geometry", False]
                volume = means["volume", True] / means["volume", False]
                rows["blades"].append(round(blades, 4))
                rows["volume"].append(round(volume, 4))
                rows["ratio"].append(round(blades / volume, 4))
            for k in table:
                table[k].append(rows[k])
    finally:
        for renderer in renderers.values():
            renderer.release()
    print(json.dumps({"direction": wind.direction, "strength": args.strength,
                      "elevations": elevations, "azimuths": azimuths, **table}))  # fmt: skip


if __name__ == "__main__":
    main()
