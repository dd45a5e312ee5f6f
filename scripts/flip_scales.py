"""At which scales the LOD frame differs from all-geometry: `sward quality`'s frame figure
(quarter-resolution FLIP over the floor) of the LOD frame with its low frequencies replaced by
the reference's (a Gaussian of sigma pixels: what is left is the difference at scales below
sigma), and of a blurred floor frame (how much smoothness alone costs). An oracle for where to
look, not a fix.

    .venv/bin/python scripts/flip_scales.py [--scene meadow] [--camera default] [--size 1024x768]

Prints JSON: the frame figure, the figure after each low-frequency correction, and the blurred
floor frame's figures."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageFilter

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

SIGMAS = (4, 8, 16, 32, 64)


def blurred(image: np.ndarray, sigma: float) -> np.ndarray:
    return np.asarray(Image.fromarray(image).filter(ImageFilter.GaussianBlur(sigma)), np.float64)


def main() -> None:
    from app.quality import QualityRun, shifted
    from app.scenes import get_scene
    from core.quality import Comparison

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="meadow")
    ap.add_argument("--camera", default="default")
    ap.add_argument("--size", default="1024x768")
    args = ap.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    document = get_scene(args.scene).document()
    camera = document.camera(args.camera)
    run = QualityRun(document, size, 1e9)
    try:
        reference, _ = run.reference(camera)
        floor_frame, _ = run.geometry.render(shifted(camera, run.blade_width), size, measure=False)
        lod, _ = run.lod_frame(camera)
    finally:
        run.release()
    floor = Comparison.of(reference, floor_frame).flip_quarter

    def figure(image: np.ndarray) -> float:
        frame = np.clip(image, 0, 255).astype(np.uint8)
        return round(Comparison.of(reference, frame).flip_quarter / floor, 2)

    lod_f = lod.astype(np.float64)
    out = {
        "scene": args.scene,
        "camera": args.camera,
        "size": list(size),
        "frame_x_floor": figure(lod_f),
        "low_frequencies_from_the_reference": {
            str(s): figure(lod_f + blurred(reference, s) - blurred(lod, s)) for s in SIGMAS
        },
        "floor_frame_blurred": {str(s): figure(blurred(floor_frame, s)) for s in (1, 2, 4)},
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
