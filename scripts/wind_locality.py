"""Is a representation's response to the gusts local? Each representation is drawn alone
(`--only`) under the scene's gusts (no turbulence, no aperiodic tiling) and under four nearly
uniform winds of the same direction (gusts 200 m across, strength 0.15 / 0.4 / 0.65 / 0.9); at
each pixel the change under the gusts (wind on − still, green channel, blurred over σ = 6 px) is
predicted by interpolating the uniform winds' changes at that pixel in the gusts' lean there.

    .venv/bin/python scripts/wind_locality.py [--direction 0] [--rows 140:200]
        [--scene bench] [--camera zones] [--save maps.npz]
    .venv/bin/python scripts/wind_locality.py --blocks maps.npz

Prints one JSON line: per representation the change's mean and spread, the prediction's, their
correlation over the rows, and the uniform winds' mean lean and change there. A correlation
near 1 says the gusts cost what a uniform lean of the local size would cost at that pixel."""

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
STRENGTHS = (0.15, 0.4, 0.65, 0.9)


def interpolate(x: np.ndarray, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """Per pixel, piecewise-linear interpolation of ys ((k, h, w)) over xs ((k, h, w), rising)
    at x, held at the ends; where two xs meet (no grass: no lean), the lower one's y."""
    x = np.clip(x, xs[0], xs[-1])
    out = ys[0].copy()
    for k in range(xs.shape[0] - 1):
        dx = xs[k + 1] - xs[k]
        t = np.where(dx > 1e-4, (x - xs[k]) / np.where(dx > 1e-4, dx, 1.0), 0.0)
        seg = ys[k] + np.clip(t, 0.0, 1.0) * (ys[k + 1] - ys[k])
        out = seg if k == 0 else np.where(x > xs[k], seg, out)
    return out


def blocks(maps) -> dict:
    """Means of the change under the third uniform lean over 30 × 120-pixel blocks, rows 90 on."""
    out: dict = {"lean": round(float(maps["uniform_leans"][2][90:].mean()), 3)}
    for mode in ("geometry", "volume"):
        change = maps[f"{mode}_uniform"][2]
        out[mode] = [
            [round(float(change[r : r + 30, c : c + 120].mean()), 1) for c in range(0, 480, 120)]
            for r in range(90, 270, 30)
        ]
    return out


def main() -> None:
    from scipy.ndimage import gaussian_filter

    from app.scenes import get_scene
    from core.wind import Wind
    from render.context import standalone
    from render.headless import HeadlessRenderer

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--direction", type=float, default=0.0, help="degrees")
    ap.add_argument("--scene", default="bench")
    ap.add_argument("--camera", default="zones")
    ap.add_argument("--rows", default="140:200", help="FIRST:END rows of the 480 × 270 frame")
    ap.add_argument(
        "--save", type=Path,
        help="an .npz of the per-pixel maps: leans, the uniform winds' and the gusts' changes",
    )  # fmt: skip
    ap.add_argument(
        "--blocks", type=Path,
        help="instead of drawing: a saved .npz's change at the third uniform lean, blades and "
        "volume, as means over blocks of 30 rows × 120 columns from row 90",
    )  # fmt: skip
    args = ap.parse_args()
    if args.blocks:
        print(json.dumps(blocks(np.load(args.blocks))))
        return
    try:
        first, end = (int(v) for v in args.rows.split(":"))
    except ValueError:
        ap.error(f"--rows {args.rows}: give FIRST:END")
    scene = dataclasses.replace(get_scene(args.scene), mirror_seed=None)
    doc = scene.document()
    camera = doc.camera(args.camera)
    ctx = standalone()

    def draw(mode: str, wind: Wind, view: str = "shaded") -> np.ndarray:
        doc.wind = wind
        with HeadlessRenderer(doc, ctx, mode=mode, view=view) as renderer:
            return renderer.render(camera, SIZE, measure=False)[0].astype(np.float64)

    def lean_size(wind: Wind) -> np.ndarray:
        lean = (draw("geometry", wind, "wind")[..., :2] / 255.0 - 0.5) * 1.8  # _wind.glsl
        return gaussian_filter(np.hypot(lean[..., 0], lean[..., 1]), SIGMA)

    # blade_reach 1: the zones as in still air (this measures the representations' response)
    gusts = doc.wind.replace(enabled=True, direction=args.direction, turbulence_strength=0.0,
                             blade_reach=1.0)  # fmt: skip
    uniform = [
        Wind(enabled=True, direction=args.direction, gust_strength=s, gust_scale=200.0,
             turbulence_strength=0.0, blade_reach=1.0)
        for s in STRENGTHS
    ]  # fmt: skip
    leans = np.stack([lean_size(w) for w in uniform])
    gust_lean = lean_size(gusts)
    rows = slice(first, end)
    out: dict = {"direction": args.direction, "rows": args.rows}
    maps: dict[str, np.ndarray] = {"uniform_leans": leans, "gust_lean": gust_lean}
    for mode in ("geometry", "volume"):
        still = draw(mode, gusts.replace(enabled=False))[..., 1]

        def change(wind: Wind, mode: str = mode, still: np.ndarray = still) -> np.ndarray:
            return gaussian_filter(draw(mode, wind)[..., 1] - still, SIGMA)

        changes = np.stack([change(w) for w in uniform])
        gust_change = change(gusts)
        maps[f"{mode}_uniform"], maps[f"{mode}_gusts"] = changes, gust_change
        actual = gust_change[rows].ravel()
        predicted = interpolate(gust_lean, leans, changes)[rows].ravel()
        out[mode] = {
            "mean": round(float(actual.mean()), 2),
            "spread": round(float(actual.std()), 2),
            "predicted_mean": round(float(predicted.mean()), 2),
            "predicted_spread": round(float(predicted.std()), 2),
            "correlation": round(float(np.corrcoef(actual, predicted)[0, 1]), 2),
            "uniform_lean": [round(float(v[rows].mean()), 3) for v in leans],
            "uniform_change": [round(float(v[rows].mean()), 2) for v in changes],
        }
    if args.save:
        maps["lod_still"] = draw("lod", gusts.replace(enabled=False))
        np.savez_compressed(args.save, **maps)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
