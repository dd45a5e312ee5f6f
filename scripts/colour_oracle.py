"""How much of `sward quality`'s figure is colour at a coarse scale: the LOD frame against its
all-geometry reference as measured, and again after the LOD frame's grass in one region has
been given the reference's local mean colour (each pixel times the ratio of the two frames'
box-filtered colours over SCALE pixels). If matching the mean colour over tens of pixels takes a
region's figure far below 2× the floor, what holds it up is light and colour that disagree over
patches of the frame, not blade detail the representation lacks.

    .venv/bin/python scripts/colour_oracle.py [--scene meadow] [--camera path] [--wind on]
        [--time 2] [--size 480x270] [--region volume] [--scales 33,17,9]
        [--box X0,Y0,X1,Y1]

With `--box` only the pixels of the region inside that rectangle are matched (e.g. one
hillside), and the two frames' mean colour there is printed. Prints one JSON document: per
region × the floor as measured, and per scale with the colour matched."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    from scipy.ndimage import uniform_filter

    from app.quality import QualityRun, shifted
    from app.scenes import get_scene
    from core.quality import Comparison, figures
    from render.grass_type import technique_colors

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="meadow")
    ap.add_argument("--camera", default="path")
    ap.add_argument("--wind", choices=("on", "off"), default="on")
    ap.add_argument("--time", type=float, default=2.0)
    ap.add_argument("--size", default="480x270")
    ap.add_argument("--region", default="volume", choices=("geometry", "volume", "image"))
    ap.add_argument("--scales", default="33,17,9")
    ap.add_argument("--box", help="X0,Y0,X1,Y1: match only the region's pixels inside it")
    args = ap.parse_args()
    try:
        width, height = (int(v) for v in args.size.split("x"))
        scales = [int(v) | 1 for v in args.scales.split(",")]  # odd: centred boxes
        box = None if args.box is None else [int(v) for v in args.box.split(",")]
    except ValueError as exc:
        ap.error(str(exc))
    size = (width, height)
    document = get_scene(args.scene).document()
    document.wind = document.wind.replace(enabled=args.wind == "on")
    camera = document.camera(args.camera)
    run = QualityRun(document, size, 1e9)
    try:
        run.set_time(args.time)
        lod, _ = run.lod_frame(camera)
        reference, _ = run.reference(camera)
        floor_image, _ = run.geometry.render(shifted(camera, run.blade_width), size, measure=False)
        run.lod.pipeline.view = "techniques"
        techniques, _ = run.lod.render(camera, size, measure=False)
    finally:
        run.release()
    _, measured, regions = figures(reference, lod, techniques, technique_colors())
    floor = Comparison.of(reference, floor_image)

    def over_floor(comparison: Comparison) -> dict:
        out = {}
        for name, mask in regions.items():
            here, base = comparison.region(mask), floor.region(mask)
            out[name] = None if here is None or not base else round(here / base, 3)
        return out

    # the region at full resolution: the quarter-resolution mask's blocks
    quarter = regions[args.region]
    full = np.zeros(lod.shape[:2], bool)
    blocks = quarter.repeat(4, axis=0).repeat(4, axis=1)
    h, w = min(blocks.shape[0], full.shape[0]), min(blocks.shape[1], full.shape[1])
    full[:h, :w] = blocks[:h, :w]
    if box is not None:
        inside = np.zeros_like(full)
        inside[box[1] : box[3], box[0] : box[2]] = True
        full &= inside
    lod_f, ref_f = lod.astype(np.float64), reference.astype(np.float64)
    result: dict = {
        "scene": args.scene,
        "camera": args.camera,
        "wind": args.wind,
        "time": args.time,
        "region": args.region,
        "box": box,
        "matched_pixels": int(full.sum()),
        "measured": over_floor(measured),
        "matched": {},
    }
    if full.any():
        result["lod_mean"] = [round(float(v), 1) for v in lod_f[full].mean(axis=0)]
        result["reference_mean"] = [round(float(v), 1) for v in ref_f[full].mean(axis=0)]
    for scale in scales:
        window = (scale, scale, 1)  # each channel's mean over scale × scale pixels
        ratio = uniform_filter(ref_f, window, mode="nearest") / np.maximum(
            uniform_filter(lod_f, window, mode="nearest"), 1.0
        )
        matched = lod_f.copy()
        matched[full] = lod_f[full] * ratio[full]
        matched = np.clip(np.rint(matched), 0, 255).astype(np.uint8)
        result["matched"][str(scale)] = over_floor(Comparison.of(reference, matched))
    print(json.dumps(result))


if __name__ == "__main__":
    main()
