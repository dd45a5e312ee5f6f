"""At which scales the LOD frame differs from all-geometry: `sward quality`'s figures (quarter-
resolution FLIP over the floor) of the LOD frame with its low frequencies replaced by the
reference's (a Gaussian of sigma pixels: what is left is the difference at scales below sigma),
and of a blurred floor frame (how much smoothness alone costs). With --regions, the same per
technique region — only that region's pixels corrected — and the region's figure had it shown
the reference blurred by sigma (a representation right at every scale above sigma and smooth
below it) or the reference's mean colour over the region. An oracle for where to look, not a
fix.

    .venv/bin/python scripts/flip_scales.py [--scene meadow | --project FILE] [--camera default]
        [--size 1024x768] [--regions]

Prints JSON: the frame figure, the figure after each low-frequency correction, the blurred
floor frame's figures, and with --regions the per-region oracles."""

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
    frame = np.clip(image, 0, 255).astype(np.uint8)
    return np.asarray(Image.fromarray(frame).filter(ImageFilter.GaussianBlur(sigma)), np.float64)


def main() -> None:
    from app.quality import QualityRun, shifted
    from app.scenes import get_scene
    from core.project_file import load_project
    from core.quality import Comparison
    from render.grass_type import technique_colors

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    source = ap.add_mutually_exclusive_group()
    source.add_argument("--scene", default="meadow")
    source.add_argument("--project", type=Path, default=None)
    ap.add_argument("--camera", default="default")
    ap.add_argument("--size", default="1024x768")
    ap.add_argument("--regions", action="store_true", help="the oracles per technique region")
    args = ap.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    if args.project is not None:
        document = load_project(args.project)
    else:
        document = get_scene(args.scene).document()
    camera = document.camera(args.camera)
    run = QualityRun(document, size, 1e9)
    try:
        reference, _ = run.reference(camera)
        floor_frame, _ = run.geometry.render(shifted(camera, run.blade_width), size, measure=False)
        lod, _ = run.lod_frame(camera)
        run.lod.pipeline.view = "techniques"
        techniques = run.lod.render(camera, size, measure=False)[0]
    finally:
        run.release()
    floor = Comparison.of(reference, floor_frame)
    colors = technique_colors()

    def figure(image: np.ndarray) -> float:
        frame = np.clip(image, 0, 255).astype(np.uint8)
        return round(Comparison.of(reference, frame).flip_quarter / floor.flip_quarter, 2)

    lod_f = lod.astype(np.float64)
    out = {
        "source": str(args.project or args.scene),
        "camera": args.camera,
        "size": list(size),
        "frame_x_floor": figure(lod_f),
        "low_frequencies_from_the_reference": {
            str(s): figure(lod_f + blurred(reference, s) - blurred(lod, s)) for s in SIGMAS
        },
        "floor_frame_blurred": {str(s): figure(blurred(floor_frame, s)) for s in (1, 2, 4)},
    }
    if args.regions:
        out["regions"] = region_oracles(reference, lod, techniques, colors, floor)
    print(json.dumps(out, indent=1))


def region_oracles(reference, lod, techniques, colors, floor) -> dict:
    """Per technique region: its figure (× the floor's over the same region) with that region's
    pixels replaced by each oracle."""
    from core.quality import Comparison, figures, technique_regions

    pixels = technique_regions(lod, techniques, colors)
    _found, _lv, quarter = figures(reference, lod, techniques, colors)
    lod_f, ref_f = lod.astype(np.float64), reference.astype(np.float64)

    def region_figure(name: str, image: np.ndarray) -> float | None:
        frame = np.clip(image, 0, 255).astype(np.uint8)
        here = Comparison.of(reference, frame).region(quarter[name])
        base = floor.region(quarter[name])
        return round(here / base, 2) if here and base else None

    result = {}
    for name, mask in pixels.items():
        if not mask.any() or name not in quarter:
            continue

        def within(replacement: np.ndarray, mask=mask) -> np.ndarray:
            image = lod_f.copy()
            image[mask] = replacement[mask]
            return image

        result[name] = {
            "lod": region_figure(name, lod_f),
            "low_frequencies_from_the_reference": {
                str(s): region_figure(name, within(lod_f + blurred(reference, s) - blurred(lod, s)))
                for s in SIGMAS
            },
            "reference_blurred": {
                str(s): region_figure(name, within(blurred(reference, s))) for s in (1, 2, 4, 8)
            },
            "reference_mean": region_figure(
                name, within(np.broadcast_to(ref_f[mask].mean(axis=0), ref_f.shape))
            ),
        }
    return result


if __name__ == "__main__":
    main()
