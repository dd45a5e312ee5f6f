"""How much the all-geometry frame's colour depends on the frame's size: a built-in scene's
camera drawn as geometry at W × H and at 2W × 2H box-halved to W × H, the mean colour of each
band of rows (0 … 255 per channel) and the difference. A renderer whose blades cover what
they should at every size shows none; `sward quality` compares the LOD frame with the
geometry at the size asked for, so a difference here is one the LOD's far field meets at one
size and not at the other.

    .venv/bin/python scripts/resolution_bias.py [--scene bench] [--camera zones] [--size 480x270]
        [--bands 100:270:40]"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="bench")
    ap.add_argument("--camera", default="zones")
    ap.add_argument("--size", default="480x270")
    ap.add_argument("--bands", default="100:270:40", help="first row:last row:rows a band")
    args = ap.parse_args()

    from app.scenes import get_scene
    from render.context import standalone
    from render.headless import HeadlessRenderer

    w, h = (int(v) for v in args.size.split("x"))
    first, last, step = (int(v) for v in args.bands.split(":"))
    doc = get_scene(args.scene).document()
    camera = doc.camera(args.camera)
    ctx = standalone()
    renderer = HeadlessRenderer(doc, ctx, mode="geometry")
    try:
        low = renderer.render(camera, (w, h), measure=False)[0][..., :3].astype(float)
        high = renderer.render(camera, (2 * w, 2 * h), measure=False)[0][..., :3].astype(float)
    finally:
        renderer.release()
        ctx.release()
    high = high.reshape(h, 2, w, 2, 3).mean(axis=(1, 3))
    print(f"{args.scene} {args.camera}: rows, {w}x{h}, {2 * w}x{2 * h} halved, difference")
    for row in range(first, min(last, h), step):
        a = low[row : row + step].mean(axis=(0, 1))
        b = high[row : row + step].mean(axis=(0, 1))
        print(
            f"  {row:4d}-{min(row + step, h) - 1:<4d} {a.round(1)}  {b.round(1)}  {(a - b).round(1)}"
        )


if __name__ == "__main__":
    main()
