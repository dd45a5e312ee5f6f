"""What each representation's region of the LOD frame shows against the blades, light term by
light term: the LOD frame and the all-geometry frame of a project's camera under diagnostic
lights, and the mean green (0 … 1) of each over the pixels each technique draws (the regions of
`sward quality`, from the frame in the technique colours).

    .venv/bin/python scripts/region_views.py PROJECT [--camera NAME] [--size 1024x768]

Views (black soil, no fog): `albedo` the scene's colours in white ambient light without AO;
`coverage` white blades, the same light (the share the grass covers); `ambient+AO` white blades
in white ambient light with the project's AO_blade; `sun` white blades lit by a white sun
alone (the diffuse factor). `ambient+AO` over `coverage` is the AO the grass shows. A project
file is written from a built-in scene with `sward new FILE --scene NAME`. Prints JSON."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

WHITE, BLACK = (1.0, 1.0, 1.0), (0.0, 0.0, 0.0)
VIEWS = {  # sun, ambient, AO as the project has it, blades white
    "albedo": (BLACK, WHITE, False, False),
    "coverage": (BLACK, WHITE, False, True),
    "ambient+AO": (BLACK, WHITE, True, True),
    "sun": (WHITE, BLACK, False, True),
}


def main() -> None:
    from core.project_file import load_project
    from core.quality import technique_regions
    from render.context import standalone
    from render.grass_type import technique_colors
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("project", type=Path)
    ap.add_argument("--camera", default=None)
    ap.add_argument("--size", default="1024x768")
    args = ap.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    ctx = standalone()
    doc = load_project(args.project)
    camera = doc.camera(args.camera)
    with HeadlessRenderer(doc, ctx) as lod:
        shaded = lod.render(camera, size, measure=False)[0]
        lod.pipeline.view = "techniques"
        techniques = lod.render(camera, size, measure=False)[0]
    regions = technique_regions(shaded, techniques, technique_colors())
    result: dict = {"project": str(args.project), "camera": args.camera, "size": size}
    for view, (sun, ambient, ao, white) in VIEWS.items():
        doc = load_project(args.project)
        if white:
            for i in range(len(doc.grass_types)):
                doc.set_params(
                    i, doc.params(i).replace(root_color=WHITE, tip_color=WHITE,
                                             blade_color_variation=0.0),
                )  # fmt: skip
        light = dict(sun_color=sun, ambient_color=ambient, soil_color=BLACK, fog_distance=1e6)
        if not ao:
            light["blade_ao_impact"] = 0.0
        doc.light = dataclasses.replace(doc.light, **light)
        green = {}
        for mode in ("geometry", "lod"):
            with HeadlessRenderer(doc, ctx, mode=mode) as renderer:
                renderer.pipeline.ground.under_grass = BLACK
                renderer.render(camera, size, measure=False)  # slices convert
                green[mode] = renderer.render(camera, size, measure=False)[0][..., 1] / 255.0
        result[view] = {
            name: {mode: round(float(g[mask].mean()), 3) for mode, g in green.items()}
            for name, mask in regions.items()
            if mask.sum() > 100
        }
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
