"""LOD against all-geometry (sward quality's figures) under a nearly uniform wind: one gust 200 m
across, no turbulence, so that every blade of the bench leans about alike (0.26 … 0.38 of its
length at strength 0.6). With docs/experiments/bent-capture.patch applied (the slices captured
from blades bent by a constant lean, the volume's shear switched off) it shows what slices of
bent blades would do to the wind-on agreement.

    .venv/bin/python scripts/uniform_wind_quality.py [--direction 90] [--strength 0.6]
        [--wind on] [--scene bench] [--camera zones] [--size 480x270] [--brightness]
        [--gusts [--turbulence S] [--gust-scale M]] [--no-tiling] [--blade-reach R]

Prints one JSON line: × the floor over the frame and per technique's region. With
`--brightness`, instead: how much each representation drawn alone (`--only`) darkens under the
wind, as the change of the green channel's mean (0 … 255) over bands of rows (the bench's zones
camera: 110–140 image-based, 140–200 volume, 200–270 geometry in the LOD frame)."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    from app.quality import QualityRun
    from app.scenes import get_scene
    from core.wind import Wind

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--direction", type=float, help="degrees (default 90, or the scene's)")
    ap.add_argument("--strength", type=float, default=0.6)
    ap.add_argument("--wind", choices=("on", "off"), default="on")
    ap.add_argument("--scene", default="bench")
    ap.add_argument("--camera", default="zones")
    ap.add_argument("--size", default="480x270")
    ap.add_argument("--brightness", action="store_true", help="--only frames' change by rows")
    ap.add_argument(
        "--gusts", action="store_true",
        help="the scene's own wind (gusts and turbulence) switched on instead of the uniform one",
    )  # fmt: skip
    ap.add_argument(
        "--no-tiling", action="store_true",
        help="every cell alike (no aperiodic tiling): a capture bent one way stays so in all",
    )  # fmt: skip
    ap.add_argument(
        "--turbulence", type=float,
        help="with --gusts: the turbulence strength instead of the scene's",
    )  # fmt: skip
    ap.add_argument(
        "--gust-scale", type=float,
        help="with --gusts: the gusts' size in world units instead of the scene's",
    )  # fmt: skip
    ap.add_argument(
        "--blade-reach", type=float, default=1.0,
        help="the wind's blade_reach (default 1: the LOD zones as in still air)",
    )  # fmt: skip
    args = ap.parse_args()
    try:
        size = tuple(int(v) for v in args.size.split("x"))
        direction = 90.0 if args.direction is None else args.direction
        wind = Wind(enabled=args.wind == "on", direction=direction,
                    gust_strength=args.strength, gust_scale=200.0,
                    turbulence_strength=0.0)  # fmt: skip
    except ValueError as exc:
        ap.error(str(exc))
    scene = get_scene(args.scene)
    if args.no_tiling:
        scene = dataclasses.replace(scene, mirror_seed=None)
    doc = scene.document()
    if args.gusts:
        wind = doc.wind.replace(enabled=args.wind == "on")
        if args.direction is not None:
            wind = wind.replace(direction=args.direction)
        if args.turbulence is not None:
            wind = wind.replace(turbulence_strength=args.turbulence)
        if args.gust_scale is not None:
            wind = wind.replace(gust_scale=args.gust_scale)
    try:
        wind = wind.replace(blade_reach=args.blade_reach)
    except ValueError as exc:
        ap.error(str(exc))
    if args.brightness:
        print(json.dumps(brightness(doc, args.camera, size, wind)))
        return
    doc.wind = wind
    run = QualityRun(doc, size, 1e9)
    try:
        row = run.camera_figures(args.camera, doc.camera(args.camera), None)
    finally:
        run.release()
    regions = {
        k: round(v["over_floor"], 2) for k, v in row["techniques"].items() if v.get("over_floor")
    }
    print(json.dumps({"wind": args.wind, "direction": wind.direction, "gusts": args.gusts,
                      "frame": round(row["over_floor"], 3), **regions}))  # fmt: skip


BANDS = ((110, 140), (140, 170), (170, 200), (200, 230), (230, 270))


def brightness(doc, camera: str, size: tuple[int, int], wind) -> dict:
    """Per representation drawn alone: the green mean's change (wind − still) per row band."""
    from core.wind import Wind
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ctx = standalone()
    out = {}
    for mode in ("geometry", "volume", "image"):
        means = []
        for blowing in (Wind(enabled=False), wind):
            doc.wind = blowing
            with HeadlessRenderer(doc, ctx, mode=mode) as renderer:
                frame = renderer.render(doc.camera(camera), size, measure=False)[0]
            means.append([float(frame[a:b, :, 1].mean()) for a, b in BANDS])
        out[mode] = [round(w - s, 1) for s, w in zip(*means, strict=True)]
    return {"rows": [f"{a}-{b}" for a, b in BANDS], **out}


if __name__ == "__main__":
    main()
