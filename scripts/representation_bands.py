"""How far each representation's colour is from the blades', by distance: every cell of a
scene's camera drawn as geometry, as volume and as image-based (`--only`), and the mean colour
of the grass in bands of screen rows (on flat ground a row is a distance) minus that of the
geometry frame. A representation that lights or colours its grass differently from the blades
shows as a trend down the rows; FLIP against all-geometry (`sward quality`) counts it over the
whole region.

    .venv/bin/python scripts/representation_bands.py [--scene bench] [--camera zones]
        [--size 480x270] [--band 15] [--only volume,image] [--height-view | --coverage-view
        | --sun-view]
        [--blades N] [--save PREFIX] [--box X0,Y0,X1,Y1 ...]

With --height-view the blades are black at the root and white at the tip, lit by white ambient
light alone without AO: a band's grey is the height along the blades that its pixels meet.
With --coverage-view the blades are white and the ground black, lit the same way: a band's grey
is the share of its pixels that the grass covers. With --sun-view the white blades are lit by a
white sun alone, over black ground: a band's grey is the diffuse factor its pixels show.

Prints JSON: per band its first row, the geometry's mean RGB (0 … 255) and each
representation's difference from it."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    from app.scenes import get_scene
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="bench")
    ap.add_argument("--camera", default="zones")
    ap.add_argument("--size", default="480x270")
    ap.add_argument("--band", type=int, default=15)
    ap.add_argument("--only", default="volume,image")
    ap.add_argument("--height-view", action="store_true")
    ap.add_argument("--coverage-view", action="store_true")
    ap.add_argument("--sun-view", action="store_true")
    ap.add_argument(
        "--blades", type=int, default=None, help="blades per patch instead of the scene's"
    )
    ap.add_argument("--save", metavar="PREFIX", help="write each frame as PREFIX-MODE.png")
    ap.add_argument(
        "--box",
        action="append",
        default=[],
        metavar="X0,Y0,X1,Y1",
        help="also the mean RGB of each frame over this rectangle (columns X0 … X1 - 1, rows "
        "Y0 … Y1 - 1); may be given more than once",
    )
    args = ap.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    scene = get_scene(args.scene)
    if args.blades is not None:
        scene = dataclasses.replace(scene, params=scene.params.replace(blade_count=args.blades))
    white = args.coverage_view or args.sun_view
    if args.height_view or white:
        root = (1.0, 1.0, 1.0) if white else (0.0, 0.0, 0.0)
        scene = scene.recoloured(root, (1.0, 1.0, 1.0))  # every grass type
    document = scene.document()
    if args.height_view or white:
        sun, ambient = ((1.0,) * 3, (0.0,) * 3) if args.sun_view else ((0.0,) * 3, (1.0,) * 3)
        document.light = dataclasses.replace(
            document.light, sun_color=sun, ambient_color=ambient, blade_ao_impact=0.0,
            soil_color=(0.0, 0.0, 0.0), fog_distance=1e6,
        )  # fmt: skip
    camera = document.camera(args.camera)
    ctx = standalone()
    images = {}
    for mode in ["geometry", *args.only.split(",")]:
        with HeadlessRenderer(document, ctx, mode=mode) as renderer:
            if white:
                renderer.pipeline.ground.under_grass = (0.0, 0.0, 0.0)
            renderer.render(camera, size, measure=False)  # slices convert, shaders compile
            image = renderer.render(camera, size, measure=False)[0]
            if args.save:
                from PIL import Image

                Image.fromarray(image).save(f"{args.save}-{mode}.png")
            images[mode] = image.astype(np.float64)
    boxes = []
    for text in args.box:
        try:
            x0, y0, x1, y1 = (int(v) for v in text.split(","))
        except ValueError:
            ap.error(f"--box {text!r}: give X0,Y0,X1,Y1")
        boxes.append(
            {"box": [x0, y0, x1, y1]}
            | {
                mode: np.round(image[y0:y1, x0:x1].reshape(-1, 3).mean(axis=0), 1).tolist()
                for mode, image in images.items()
            }
        )
    reference = images.pop("geometry")
    sky = np.abs(reference - reference[0, 0]).sum(axis=-1) < 4  # the sky's colour
    bands = []
    for y0 in range(0, size[1], args.band):
        rows = slice(y0, y0 + args.band)
        grass = ~sky[rows]
        if grass.sum() < 100:
            continue
        geometry = reference[rows][grass].mean(axis=0)
        row = {"row": y0, "geometry": np.round(geometry, 1).tolist()}
        for mode, image in images.items():
            row[mode] = np.round(image[rows][grass].mean(axis=0) - geometry, 1).tolist()
        bands.append(row)
    out = {"scene": args.scene, "camera": args.camera, "size": size, "bands": bands}
    if boxes:
        out["boxes"] = boxes
    print(json.dumps(out))


if __name__ == "__main__":
    main()
