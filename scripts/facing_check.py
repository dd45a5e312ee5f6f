"""How bright a far representation lights one grass type against its blades, by view: the
bench's cells with a project's grass type (white blades, black soil, no AO, no fog), flat or on
a ramp rising away from -z, seen from a camera at a distance, elevation and azimuth around the
grid's centre; each representation drawn for every cell (`--only`) under a sun-only view and an
ambient-only view. Sun over ambient over the window is the diffuse factor the grass shows
(core/facing.py's table for the image-based grass), coverage the share of the window covered.

    .venv/bin/python scripts/facing_check.py PROJECT [--type 1] [--distance 20]
        [--height-scale 0] [--elevations 5,10,20] [--azimuths 0,90,180,270]
        [--modes geometry,image] [--predict] [--wind DIRECTION,STRENGTH]
        [--sun-elevation DEGREES] [--sun-azimuth DEGREES] [--translucency T]

`--wind` blows a wind of one gust over the grid (gusts 200 m across, no turbulence): the lean
at the grid's centre is printed with each view. Azimuth 0 puts the camera at -z looking
towards +z (up the ramp). Prints one JSON line a view."""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

WHITE, BLACK = (1.0, 1.0, 1.0), (0.0, 0.0, 0.0)
SIZE = (320, 180)
WINDOW = (slice(70, 110), slice(100, 220))
CENTRE = 0.0  # the centre of the bench's 32 × 32 cells (its origin is at -16, -16)


def main() -> None:
    from app.scenes import CameraSpec, get_scene
    from core.project_file import load_project
    from core.slopes import slope_moments
    from core.wind import Wind, lean
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("project", type=Path)
    ap.add_argument("--type", type=int, default=0)
    ap.add_argument("--distance", type=float, default=20.0)
    ap.add_argument("--height-scale", type=float, default=0.0)
    ap.add_argument("--elevations", default="5,10,20")
    ap.add_argument("--azimuths", default="0,90,180,270")
    ap.add_argument("--modes", default="geometry,image")
    ap.add_argument(
        "--predict", action="store_true",
        help="also core/slopes.py slope_moments' upright and sheared diffuse factor at each view",
    )  # fmt: skip
    ap.add_argument(
        "--wind", default=None,
        help="DIRECTION,STRENGTH: a nearly uniform wind (degrees, gust strength), else still air",
    )  # fmt: skip
    ap.add_argument("--sun-elevation", type=float, help="degrees (default: the project's)")
    ap.add_argument("--sun-azimuth", type=float, help="degrees (default: the project's)")
    ap.add_argument("--translucency", type=float, help="0 … 1 (default: the project's)")
    args = ap.parse_args()
    wind = Wind()
    if args.wind:
        try:
            direction, strength = (float(v) for v in args.wind.split(","))
            # blade_reach 1: the zones as in still air
            wind = Wind(enabled=True, direction=direction, gust_strength=strength,
                        gust_scale=200.0, turbulence_strength=0.0, blade_reach=1.0)  # fmt: skip
        except ValueError as exc:
            ap.error(f"--wind {args.wind}: give DIRECTION,STRENGTH ({exc})")
    project = load_project(args.project)
    if args.sun_elevation is not None:
        project.light = dataclasses.replace(project.light, sun_elevation=args.sun_elevation)
    if args.sun_azimuth is not None:
        project.light = dataclasses.replace(project.light, sun_azimuth=args.sun_azimuth)
    if args.translucency is not None:
        project.light = dataclasses.replace(project.light, translucency=args.translucency)
    params = project.params(args.type).replace(
        root_color=WHITE, tip_color=WHITE, blade_color_variation=0.0
    )
    hs = args.height_scale

    def ramp(width: int, height: int) -> np.ndarray:
        return np.repeat(np.linspace(0.0, 1.0, height, dtype=np.float32)[:, None], width, axis=1)

    scene = dataclasses.replace(get_scene("bench"), params=params, height_map=ramp, height_scale=hs)
    ctx = standalone()
    model = None
    if args.predict:  # the type's patch and canopy, as the renderer holds them
        doc = scene.document()
        with HeadlessRenderer(doc, ctx, mode="image") as renderer:
            renderer.render(doc.camera("default"), (64, 36), measure=False)
            grass = renderer.pipeline.grass_types[0]
            model = (grass.patch.vertices, grass.image.textures.canopy)
    for elevation in (float(v) for v in args.elevations.split(",")):
        for azimuth in (float(v) for v in args.azimuths.split(",")):
            el, az = math.radians(elevation), math.radians(azimuth)
            level = args.distance * math.cos(el)
            eye = (
                CENTRE + level * math.sin(az),
                args.distance * math.sin(el) + 0.5 * hs,
                CENTRE - level * math.cos(az),
            )
            camera_spec = CameraSpec(eye, (CENTRE, 0.5 * hs, CENTRE), 300.0)
            placed = dataclasses.replace(scene, cameras={"default": camera_spec})
            row: dict = {"elevation": elevation, "azimuth": azimuth, "height_scale": hs}
            if wind.enabled:
                centre = lean(wind, np.array([CENTRE, CENTRE]), 0.0)
                row["lean"] = [round(float(v), 3) for v in centre]
            for mode in args.modes.split(","):
                seen = {}
                for view, (sun, ambient) in {
                    "ambient": (BLACK, WHITE),
                    "sun": (WHITE, BLACK),
                }.items():
                    doc = placed.document()
                    doc.wind = wind
                    doc.light = dataclasses.replace(
                        project.light, sun_color=sun, ambient_color=ambient, soil_color=BLACK,
                        sky_color=BLACK,
                        fog_distance=1e6, blade_ao_impact=0.0,
                    )  # fmt: skip
                    camera = doc.camera("default")
                    with HeadlessRenderer(doc, ctx, mode=mode) as renderer:
                        renderer.pipeline.ground.under_grass = BLACK
                        renderer.render(camera, SIZE, measure=False)  # slices convert
                        frame = renderer.render(camera, SIZE, measure=False)[0]
                    seen[view] = float(frame[..., 1][WINDOW].mean()) / 255.0
                row[mode] = {
                    "coverage": round(seen["ambient"], 3),
                    "diffuse": round(seen["sun"] / max(seen["ambient"], 1e-6), 3),
                }
            if model is not None:
                to_eye = np.subtract(eye, camera_spec.target)
                away = -to_eye[[0, 2]] / np.linalg.norm(to_eye[[0, 2]])
                rise = away[1] * hs / 32.0  # the ramp rises along z over the bench's 32 cells
                across = away[0] * hs / 32.0  # and to the right of the view ((-away z, away x))
                theta = math.atan(math.tan(el) + rise)
                vertices, canopy = model
                sums = slope_moments(
                    vertices["normal"], vertices["position"], vertices["root"], canopy,
                    to_eye[None, :], np.array([theta]), across=np.array([across]),
                )  # fmt: skip
                light = (project.light.sun_direction, project.light.translucency)
                upright, sheared = (part.lit(*light) for part in sums)
                row["model"] = {"upright": round(float(upright[0]), 3),
                                "sheared": round(float(sheared[0]), 3)}  # fmt: skip
                if wind.enabled:
                    still, bent = lean_means(
                        vertices, canopy, project.light.sun_direction,
                        project.light.translucency, to_eye[None, :],
                        np.array([[0.0, 0.0], row["lean"]]),
                    )[:, 0]  # fmt: skip
                    row["model"]["bent_over_still"] = round(float(bent / still), 4)
            print(json.dumps(row), flush=True)


def lean_means(vertices, canopy, light_dir, translucency, to_eye, leans):
    """The blades' mean diffuse factor seen from `to_eye` ((m, 3)) with every blade bent by
    each tip displacement of `leans` ((j, 2)): (j, m). core/slopes.py's slope_moments weigh the
    bent normals (on flat ground its sheared mean: |n · e| times the share of a view from e's
    elevation that reaches the vertex), at the vertices' bent heights, the bent canopy stretched
    back to its height at rest (weighing them at their heights at rest, the model predicted
    brighter blades where they measure darker). The model of a table for the far
    representations under the wind: it holds looking down, not at grazing views (docs/wind.md,
    wind)."""
    from core.slopes import slope_moments
    from core.wind import bend_vertices

    e = np.asarray(to_eye, np.float64).reshape(-1, 3)
    theta = np.arcsin(e[:, 1] / np.linalg.norm(e, axis=1))[None, :]
    rest_top = np.percentile(vertices["position"][:, 1], 99)
    out = np.zeros((len(leans), len(e)))
    for j, lean_xz in enumerate(np.asarray(leans, np.float64).reshape(-1, 2)):
        bent, normals = bend_vertices(vertices, lean_xz)
        bent[:, 1] *= rest_top / max(np.percentile(bent[:, 1], 99), 1e-9)
        sheared = slope_moments(normals, bent, vertices["root"], canopy, e, theta)[1]
        out[j] = sheared.lit(light_dir, translucency)[0]
    return out


if __name__ == "__main__":
    main()
