"""How far all-geometry frames from cameras moved sideways score against the reference, in
`sward quality`'s terms: a yardstick for its goals. The floor is two reference frames a blade's
width apart; a frame from a few decimetres aside shows the same grass with every blade seen
from elsewhere, which is what any representation that does not place each blade where it is
would show at best.

    .venv/bin/python scripts/shifted_views.py SOURCE --camera NAME --size WxH [--shifts 0.1,0.37]

SOURCE is a built-in scene or a project file. Per shift: the frame's quarter-resolution FLIP
over the floor's, and over each technique region of the LOD frame."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    from app.quality import QualityRun, shifted
    from app.scenes import get_scene
    from core.project_file import load_project
    from core.quality import Comparison, figures
    from render.grass_type import technique_colors

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("source", help="built-in scene or project file")
    ap.add_argument("--camera", default=None)
    ap.add_argument("--size", default="480x270")
    ap.add_argument("--shifts", default="0.1,0.37", help="metres aside, comma-separated")
    args = ap.parse_args()
    source = Path(args.source)
    document = (
        load_project(source) if source.suffix == ".sward" else get_scene(args.source).document()
    )
    size = tuple(int(v) for v in args.size.split("x"))
    camera = document.camera(args.camera or document.default_camera)
    run = QualityRun(document, size, 1e9)  # type: ignore[arg-type]
    try:
        reference, _ = run.reference(camera)
        floor_image, _ = run.geometry.render(shifted(camera, run.blade_width), size, measure=False)
        lod_image, _ = run.lod_frame(camera)
        run.lod.pipeline.view = "techniques"
        tech, _ = run.lod.render(camera, size, measure=False)
        run.lod.pipeline.view = "shaded"
        _, lod, regions = figures(reference, lod_image, tech, technique_colors())
        floor = Comparison.of(reference, floor_image)

        def row(name: str, c: Comparison) -> str:
            parts = [f"{name:>18s}: frame {c.flip_quarter / floor.flip_quarter:.2f}x the floor"]
            for technique, region in regions.items():
                here, base = c.region(region), floor.region(region)
                if here is not None and base:
                    parts.append(f"{technique} {here / base:.2f}x")
            return ", ".join(parts)

        print(f"{args.source} {args.camera or document.default_camera} {args.size}")
        print(row("LOD", lod))
        for shift in (float(v) for v in args.shifts.split(",")):
            image, _ = run.geometry.render(shifted(camera, shift), size, measure=False)
            print(row(f"geometry {shift:g} m aside", Comparison.of(reference, image)))
    finally:
        run.release()


if __name__ == "__main__":
    main()
