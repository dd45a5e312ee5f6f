"""Where a frame lets the ground show through the grass: the LOD frame (or one representation,
`--only`) drawn with the soil under the grass magenta, and for the magenta pixels the world
points where their rays meet the terrain and those points' distances from the eye.

    .venv/bin/python scripts/ground_holes.py [--scene meadow | --project FILE]
        [--camera default | --eye X,Y,Z --target X,Y,Z] [--size 1024x768]
        [--only geometry|volume|image]
        [--window X0,Y0,X1,Y1]

Prints JSON: the number of magenta pixels in the window and their share of it, and up to 60
of their ground points (x, z) with their distances."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    from app.scenes import get_scene
    from core.picking import ground_hit, pixel_ray
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="meadow")
    ap.add_argument("--project", default=None, help="a project file instead of --scene")
    ap.add_argument("--camera", default="default")
    ap.add_argument("--eye", default=None, help="X,Y,Z instead of --camera (with --target)")
    ap.add_argument("--target", default=None, help="X,Y,Z the eye looks at")
    ap.add_argument("--size", default="1024x768")
    ap.add_argument("--only", default="lod", help="geometry, volume or image (default: LOD)")
    ap.add_argument("--window", default=None, help="pixels X0,Y0,X1,Y1 (default: the frame)")
    args = ap.parse_args()
    w, h = (int(v) for v in args.size.split("x"))
    x0, y0, x1, y1 = (int(v) for v in args.window.split(",")) if args.window else (0, 0, w, h)
    if args.project is not None:
        from core.project_file import load_project

        document = load_project(args.project)
    else:
        document = get_scene(args.scene).document()
    if args.eye is not None:
        from core.camera import Camera

        eye, target = (tuple(float(v) for v in p.split(",")) for p in (args.eye, args.target))
        camera = Camera.from_eye_target(eye, target)
    else:
        camera = document.camera(args.camera)
    with HeadlessRenderer(document, standalone(), mode=args.only) as renderer:
        renderer.pipeline.ground.under_grass = (1.0, 0.0, 1.0)
        renderer.render(camera, (w, h), measure=False)
        image = renderer.render(camera, (w, h), measure=False)[0].astype(np.int32)
    window = image[y0:y1, x0:x1]
    magenta = (window[..., 0] > 180) & (window[..., 2] > 180) & (window[..., 1] < 90)
    ys, xs = np.nonzero(magenta)
    step = max(1, len(xs) // 60)
    points = []
    for x, y in list(zip(xs + x0, ys + y0, strict=True))[::step]:
        hit = ground_hit(document.terrain, *pixel_ray(camera, x + 0.5, y + 0.5, w, h))
        if hit is not None:
            distance = float(np.hypot(hit[0] - camera.eye[0], hit[2] - camera.eye[2]))
            points.append([round(float(hit[0]), 2), round(float(hit[2]), 2), round(distance, 1)])
    share = round(float(magenta.mean()), 4)
    print(json.dumps({"pixels": int(magenta.sum()), "share": share, "points_x_z_distance": points}))


if __name__ == "__main__":
    main()
