"""A copy of a project that keeps some of its grass types: the others' blades, slices and
density channels go unused, everything else (terrain, maps, light, cameras, LOD of the kept
types) stays. For measuring how much of `sward quality`'s figure one type's representations
make, e.g. the meadow's tall grass over its main grass.

    .venv/bin/python scripts/keep_types.py PROJECT OUT --types 0[,1 …]"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))


def main() -> None:
    from core.document import Document
    from core.project_file import load_project, save_project

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("project", type=Path)
    ap.add_argument("out", type=Path)
    ap.add_argument("--types", required=True, help="indices of the grass types to keep")
    args = ap.parse_args()
    doc = load_project(args.project)
    keep = [int(v) for v in args.types.split(",")]
    if not keep or any(not 0 <= i < len(doc.grass_types) for i in keep):
        sys.exit(
            f"--types: {args.types!r} — {args.project} has types 0 … {len(doc.grass_types) - 1}"
        )
    kept = Document(
        doc.name, [doc.grass_types[i] for i in keep], doc.terrain_spec, doc.maps,
        description=doc.description, density=doc.density, slices=doc.slices, light=doc.light,
        cameras=doc.cameras, default_camera=doc.default_camera, paths=doc.paths, props=doc.props,
    )  # fmt: skip
    save_project(args.out, kept)
    print(f"wrote {args.out}: {', '.join(g.name for g in kept.grass_types)}")


if __name__ == "__main__":
    main()
