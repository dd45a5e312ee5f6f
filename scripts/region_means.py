"""The mean colour of each representation's region of the LOD frame against the all-geometry
frame at the same camera, in the scene's own light (0 … 255 per channel; the regions of
`sward quality`, from the frame in the technique colours).

    .venv/bin/python scripts/region_means.py SOURCE:CAMERA:WxH [...]

SOURCE is a built-in scene's name or a project file (.sward). Prints a line per region."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("views", nargs="+", help="SOURCE:CAMERA:WxH")
    args = ap.parse_args()

    from app.quality import QualityRun
    from app.scenes import get_scene
    from core.project_file import load_project
    from core.quality import technique_regions
    from render.grass_type import technique_colors

    for view in args.views:
        source, camera_name, size = view.rsplit(":", 2)
        w, h = (int(v) for v in size.split("x"))
        doc = load_project(source) if source.endswith(".sward") else get_scene(source).document()
        run = QualityRun(doc, (w, h), budget_s=1e9)
        try:
            camera = doc.camera(camera_name)
            lod, _ = run.lod_frame(camera)
            reference, _ = run.reference(camera)
            run.lod.pipeline.view = "techniques"
            techniques, _ = run.lod.render(camera, (w, h), measure=False)
        finally:
            run.release()
        print(view)
        for name, mask in technique_regions(lod, techniques, technique_colors()).items():
            if not mask.any():
                continue
            a = lod[..., :3][mask].astype(float).mean(axis=0)
            b = reference[..., :3][mask].astype(float).mean(axis=0)
            print(
                f"  {name:9s} {int(mask.sum()):7d} px  LOD {a.round(1)}  geometry {b.round(1)}  "
                f"difference {(a - b).round(1)}"
            )


if __name__ == "__main__":
    main()
