"""How strongly each representation's light follows the lean of the scene's gusts: the change
of the green channel (wind on − still, each drawn alone with `--only`, blurred over σ = 6 px)
over a band of rows, fitted against the lean's size there (from `--view wind`, blurred alike):
change ≈ slope · |lean| + offset. The blades and the volume should follow it alike.

    .venv/bin/python scripts/wind_response.py [--direction 0] [--scene bench] [--camera zones]
        [--rows 140:200] [--tiling] [--turbulence S] [--gust-scale M]

Prints one JSON line: per representation the slope, offset, R² and the change's mean and
spread, and the correlation of the two changes. Without --tiling every cell is alike."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

SIZE = (480, 270)
SIGMA = 6.0


def main() -> None:
    from scipy.ndimage import gaussian_filter

    from app.scenes import get_scene
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--direction", type=float, help="degrees (default: the scene's wind)")
    ap.add_argument("--scene", default="bench")
    ap.add_argument("--camera", default="zones")
    ap.add_argument("--rows", default="140:200", help="FIRST:END rows of the 480 × 270 frame")
    ap.add_argument("--tiling", action="store_true", help="keep the aperiodic tiling")
    ap.add_argument("--turbulence", type=float, help="turbulence strength (default: the scene's)")
    ap.add_argument(
        "--gust-scale", type=float, help="gust size in world units (default: the scene's)"
    )
    args = ap.parse_args()
    try:
        first, end = (int(v) for v in args.rows.split(":"))
    except ValueError:
        ap.error(f"--rows {args.rows}: give FIRST:END")
    scene = get_scene(args.scene)
    if not args.tiling:
        scene = dataclasses.replace(scene, mirror_seed=None)
    doc = scene.document()
    camera = doc.camera(args.camera)
    wind = doc.wind.replace(enabled=True, blade_reach=1.0)  # the zones as in still air
    if args.direction is not None:
        wind = wind.replace(direction=args.direction)
    if args.turbulence is not None:
        wind = wind.replace(turbulence_strength=args.turbulence)
    if args.gust_scale is not None:
        wind = wind.replace(gust_scale=args.gust_scale)
    ctx = standalone()

    def draw(mode: str, on: bool, view: str = "shaded") -> np.ndarray:
        doc.wind = wind.replace(enabled=on)
        with HeadlessRenderer(doc, ctx, mode=mode, view=view) as renderer:
            return renderer.render(camera, SIZE, measure=False)[0].astype(np.float64)

    rows = slice(first, end)
    lean = (draw("geometry", True, "wind")[..., :2] / 255.0 - 0.5) * 1.8  # shaders/_wind.glsl
    size = gaussian_filter(np.hypot(lean[..., 0], lean[..., 1]), SIGMA)[rows].ravel()
    fit = np.stack([size, np.ones(size.size)], axis=1)
    out: dict = {"direction": wind.direction, "rows": args.rows}
    changes = {}
    for mode in ("geometry", "volume"):
        change = draw(mode, True)[..., 1] - draw(mode, False)[..., 1]
        change = gaussian_filter(change, SIGMA)[rows].ravel()
        (slope, offset), *_ = np.linalg.lstsq(fit, change, rcond=None)
        residual = change - fit @ (slope, offset)
        r2 = 1.0 - (residual**2).sum() / max(((change - change.mean()) ** 2).sum(), 1e-12)
        changes[mode] = change
        out[mode] = {"slope": round(float(slope), 2), "offset": round(float(offset), 2),
                     "r2": round(float(r2), 2), "mean": round(float(change.mean()), 2),
                     "spread": round(float(change.std()), 2)}  # fmt: skip
    out["correlation"] = round(float(np.corrcoef(changes["geometry"], changes["volume"])[0, 1]), 2)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
