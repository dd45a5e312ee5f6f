"""`sward export --what slices`: each grass type's slices (thesis 4.2) as PNG atlases with a
JSON description of their layout, every mip level Sward computed (4.2.2-4.2.3: alpha-weighted
colour, coverage kept by the max-alpha levels, colour bled from the next level).

    DIR/slices/<type>-<N>/layout.json        what each file holds, the slices' placement
    DIR/slices/<type>-<N>/<family>-color-<k>.png   8-bit RGBA: albedo and alpha
    DIR/slices/<type>-<N>/<family>-data-<k>.png    16-bit RGBA: normal (xyz · 0.5 + 0.5, turned
                                                   to face up) and the density threshold

for every slice count N a volume level of the type uses and the image-based level's, with the
families x (N slabs across x, u along z), z (across z, u along x) and top (the one horizontal
slice, u along x, v along z). Conversion draws on a GL context of its own (render/conversion.py),
as the renderer does."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import numpy as np

FAMILIES = {
    "x": "slabs across x: slice i holds the blades between x = i/N and (i+1)/N, seen along +x; "
    "u runs along z, v up the patch (row 0 at the ground)",
    "z": "slabs across z: slice i holds the blades between z = i/N and (i+1)/N, seen along +z; "
    "u runs along x, v up the patch (row 0 at the ground)",
    "top": "the whole patch seen from above: u along x, v along z (row 0 at z = 0)",
}


def slice_counts(document, kind) -> list[int]:
    """The slice counts a grass type is drawn with: its volume levels' and the image-based
    level's (the top slice of the document's slice parameters)."""
    counts = {lv.slices for lv in kind.lod.levels if lv.representation == "volume"}
    return sorted(counts | {document.slices.slices})


def export_slices(document, out: Path, say: Callable[[str], None]) -> dict:
    from app.export import file_name, png16
    from core.patch import generate_patch
    from render.context import standalone
    from render.conversion import PatchConverter
    from render.slices import SliceLevels

    sp = document.slices
    ctx = standalone()
    converter = PatchConverter(ctx)
    written: dict = {}
    try:
        for kind in document.grass_types:
            patch = generate_patch(kind.params)
            for n in slice_counts(document, kind):
                sliced = converter.convert(patch, n, (sp.width, sp.height), sp.top)
                levels = SliceLevels.compute(sliced)
                folder = out / "slices" / f"{file_name(kind.name)}-{n}"
                folder.mkdir(parents=True, exist_ok=True)
                layout = _layout(kind.name, n, sliced.height, sp)
                for family in FAMILIES:
                    chain = getattr(levels, family)
                    entries = []
                    for k, (color, data) in enumerate(zip(chain.color, chain.data, strict=True)):
                        names = (f"{family}-color-{k}.png", f"{family}-data-{k}.png")
                        _png8(folder / names[0], color)
                        png16(folder / names[1], data)
                        h, w = color.shape[:2]
                        entries.append(
                            {"level": k, "size": [w, h], "color": names[0], "data": names[1]}
                        )
                    layout["families"][family]["levels"] = entries
                (folder / "layout.json").write_text(json.dumps(layout, indent=1) + "\n")
                written[f"{kind.name} {n}"] = str(folder.relative_to(out))
                say(f"{kind.name}: {n} slices per direction")
    finally:
        converter.release()
        ctx.release()
    return written


def _layout(name: str, n: int, height: float, sp) -> dict:
    return {
        "format": "sward-slices",
        "version": 1,
        "grass_type": name,
        "slices": n,
        "spacing": 1.0 / n,  # cell units between neighbouring slices of one family
        "patch_height": height,  # world units the vertical slices' v = 1 stands for
        "slice_size": [sp.width, sp.height],  # one vertical slice at level 0 (u, v texels)
        "top_size": [sp.top, sp.top],
        "color": "albedo (linear, not premultiplied) and alpha, 8-bit",
        "data": "normal · 0.5 + 0.5 in RGB (patch space, turned to face up: y ≥ 0) and the "
        "density threshold in A (0 where empty), 16-bit",
        "families": {
            family: {
                "meaning": text,
                "count": 1 if family == "top" else n,
                # vertical slices are stacked along v: slice i in rows i·h … (i+1)·h − 1 of a
                # level whose height is count · h
                "stacked": "along v" if family != "top" else "one slice",
            }
            for family, text in FAMILIES.items()
        },
    }


def _png8(path: Path, values: np.ndarray) -> None:
    from PIL import Image

    rgba = np.round(np.clip(np.nan_to_num(values), 0.0, 1.0) * 255.0).astype(np.uint8)
    Image.fromarray(rgba, "RGBA").save(path, format="PNG")
