"""How much soil shows between the grass: the bench's cells on a ramp (or flat), seen from a
camera above its low end, drawn as geometry and as one other representation (`--only`), each
twice, with the soil under the grass black and white; the difference of the two frames, over
the ground's own darkening under grass (shaders/ground.glsl: AO 0.6 where the density map is
1), is the share of each pixel the soil shows through. White blades under white ambient light
alone.

    .venv/bin/python scripts/soil_share.py [--height-scale 16] [--blades 500] [--only image]
        [--eye X,Y,Z]

Prints JSON: the share over the grass and per band of 20 rows, for each representation."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

SIZE = (320, 180)
WINDOW = (slice(60, 160), slice(60, 260))  # rows and columns over the ramp's grass
GROUND_AO = 0.6  # shaders/ground.glsl: the soil under full-density grass


def ramp(width: int, height: int) -> np.ndarray:
    """0 at the camera's end of the grid, 1 at the far end."""
    return np.repeat(np.linspace(0.0, 1.0, height, dtype=np.float32)[:, None], width, axis=1)


def main() -> None:
    from app.scenes import CameraSpec, get_scene
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--height-scale", type=float, default=16.0, help="0: flat")
    ap.add_argument("--blades", type=int, default=None, help="blades per patch (bench: 2400)")
    ap.add_argument("--only", default="image")
    ap.add_argument("--eye", default="0,20,-40", help="camera position (it looks at 0,8,0)")
    args = ap.parse_args()
    scene = get_scene("bench").recoloured((1.0, 1.0, 1.0), (1.0, 1.0, 1.0))
    if args.blades is not None:
        scene = dataclasses.replace(scene, params=scene.params.replace(blade_count=args.blades))
    scene = dataclasses.replace(
        scene,
        height_map=ramp,
        height_scale=args.height_scale,
        cameras={
            "default": CameraSpec(
                tuple(float(v) for v in args.eye.split(",")), (0.0, 8.0, 0.0), 300.0
            )
        },
    )
    document = scene.document()
    document.light = dataclasses.replace(
        document.light, sun_color=(0.0, 0.0, 0.0), ambient_color=(1.0, 1.0, 1.0),
        blade_ao_impact=0.0, fog_distance=1e6,
    )  # fmt: skip
    camera = document.camera("default")
    ctx = standalone()
    result = {"height_scale": args.height_scale, "blades": document.params(0).blade_count}
    for mode in ("geometry", args.only):
        with HeadlessRenderer(document, ctx, mode=mode) as renderer:
            frames = []
            for soil in (0.0, 1.0):
                renderer.pipeline.ground.under_grass = (soil, soil, soil)
                renderer.render(camera, SIZE, measure=False)
                frames.append(renderer.render(camera, SIZE, measure=False)[0] / 255.0)
        share = (frames[1] - frames[0]).mean(axis=-1)[WINDOW] / GROUND_AO
        result[mode] = {
            "soil_share": round(float(share.mean()), 4),
            "bands": [round(float(share[y : y + 20].mean()), 4) for y in range(0, len(share), 20)],
        }
    print(json.dumps(result))


if __name__ == "__main__":
    main()
