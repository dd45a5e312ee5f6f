"""What the blades themselves show where the sweep's checks miss: a sweep case's LOD frame
against its all-geometry frame drawn `--supersample` times larger and reduced (so that the
blades' own aliasing does not count), through the case's camera or through a narrower one at
the same focal length aimed at a pixel (`--window X,Y,HEIGHT`: the LOD levels stay as they are
and only that part of the frame is drawn, so that all-geometry is affordable far away).

    .venv/bin/python scripts/blade_reference.py --case landscape/valley --window 240,95,48
    .venv/bin/python scripts/blade_reference.py --case meadow/default --wind --supersample 8 --block 16

Prints one JSON line: the soil share (the soil under the grass drawn magenta) and the mean
colour of each frame; with --wind, per representation's region the mean per-pixel change
between the wind's moments 0 and 0.5 s, and with --block K that of the means of K × K blocks
wholly in the region (the gusts' waves, without the change of single blades inside a pixel).
The region is the LOD frame's (technique colours); all-geometry of a landscape takes
minutes."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def blocks(image: np.ndarray, k: int) -> np.ndarray:
    """The means of the k × k blocks of an (h, w, c) image (the ragged edge dropped)."""
    h, w = image.shape[0] // k * k, image.shape[1] // k * k
    return image[:h, :w].reshape(h // k, k, w // k, k, -1).mean(axis=(1, 3))


def main() -> None:
    from app.sweep import cases

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", default="meadow/default")
    parser.add_argument("--size", default="480x270")
    parser.add_argument("--supersample", type=int, default=1)
    parser.add_argument("--window", help="X,Y,HEIGHT: a window of the frame about pixel X, Y")
    parser.add_argument("--wind", action="store_true")
    parser.add_argument("--block", type=int, default=0, help="K: also the change of K × K blocks")
    args = parser.parse_args()
    case = next((c for c in cases() if c.name == args.case), None)
    if case is None:
        sys.exit(f"--case: no sweep case {args.case!r}")
    document = case.document()
    camera = document.camera(case.camera)
    width, height = (int(v) for v in args.size.split("x"))
    if args.window:
        camera, width, height = window_camera(camera, args.window, width, height)
    if args.wind:
        document.wind = document.wind.replace(enabled=True)
    print(json.dumps(compare(args, document, camera, width, height)))


def window_camera(camera, window: str, width: int, height: int):
    """A camera `rows` pixels high about pixel (x, y) of `camera`'s frame; its size."""
    from core.camera import Camera

    x, y, rows = (float(v) for v in window.split(","))
    eye = camera.eye
    ahead = np.asarray(camera.target) - eye
    ahead /= np.linalg.norm(ahead)
    right = np.cross(ahead, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, ahead)
    t = math.tan(math.radians(camera.fov_y) / 2.0)
    ray = ahead + (right * (x - width / 2) + up * (height / 2 - y)) / (height / 2) * t
    fov = 2.0 * math.degrees(math.atan(t * rows / height))
    narrow = Camera.from_eye_target(eye, eye + ray, fov_y=fov, near=camera.near, far=camera.far)
    return narrow, int(2 * rows), int(rows)


def compare(args, document, camera, width: int, height: int) -> dict:
    """The LOD frame's and the (supersampled) blades' soil share, mean colour and, with the
    wind, change between 0 and 0.5 s per representation's region."""
    from app.sweep import MAGENTA
    from core.image_diff import to_float
    from core.quality import technique_regions
    from render.grass_type import technique_colors
    from render.headless import HeadlessRenderer

    def frames(mode: str, scale: int) -> dict:
        size = (width * scale, height * scale)
        out = {}
        with HeadlessRenderer(document, mode=mode) as renderer:

            def draw() -> np.ndarray:
                image = to_float(renderer.render(camera, size, measure=False)[0])
                return image.reshape(height, scale, width, scale, -1).mean(axis=(1, 3))

            if mode == "lod":
                renderer.pipeline.view = "techniques"
                out["techniques"] = draw()
                renderer.pipeline.view = "shaded"
            out["shaded"] = draw()
            kept = renderer.pipeline.ground.under_grass
            renderer.pipeline.ground.under_grass = MAGENTA
            out["soil"] = draw()
            renderer.pipeline.ground.under_grass = kept
            if args.wind:
                renderer.pipeline.time = 0.5
                out["later"] = draw()
        return out

    lod, blades = frames("lod", 1), frames("geometry", args.supersample)
    regions = technique_regions(lod["shaded"], lod["techniques"], technique_colors())
    result: dict = {"case": args.case, "window": args.window, "supersample": args.supersample}
    for name, f in (("lod", lod), ("blades", blades)):
        moved = (f["soil"][..., 2] - f["soil"][..., 1]) - (
            f["shaded"][..., 2] - f["shaded"][..., 1]
        )
        row = {
            "soil": round(float(np.clip(moved, 0.0, 1.0).mean()), 4),
            "rgb": [round(float(v), 4) for v in f["shaded"].reshape(-1, 3).mean(axis=0)],
        }
        if args.wind:
            change = np.abs(f["later"] - f["shaded"]).mean(axis=-1)
            for region, mask in regions.items():
                if mask.sum() >= 64:
                    row[f"change_{region}"] = round(float(change[mask].mean()), 5)
                if args.block > 1:
                    whole = blocks(mask[..., None].astype(np.float64), args.block)[..., 0] > 0.999
                    moved = np.abs(blocks(f["later"], args.block) - blocks(f["shaded"], args.block))
                    if whole.any():
                        row[f"block_change_{region}"] = round(
                            float(moved.mean(-1)[whole].mean()), 5
                        )
        result[name] = row
    return result


if __name__ == "__main__":
    main()
