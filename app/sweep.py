"""`sward quality --sweep`: the checks that guard the far field, over every built-in scene at
every named camera and the meadow with each preset and each patch extreme. Per case, the LOD
frame (core/quality.py has the figures):

- bare blocks: the share of 8 × 8 blocks of terrain whose soil shows through more than half
  (the frame drawn again with the soil under the grass magenta);
- hand-over steps: the brightness step between neighbouring blocks where LOD levels meet or
  hand over, against the step inside one level (mean and 95th percentile);
- where the all-geometry reference is affordable (the meadow, the bench, the patch grid): each
  representation's region mean colour against the reference's same region, and the hand-over
  steps against the reference's steps across the same blocks;
- each representation's pattern at the scale of stripes against the all-geometry frame's over
  the same region (checked on the DEM, whose slopes showed stripes);
- the football: how continuous each touchline is (core/quality.py line_gaps), where it shows;
- the meadow with the wind: how much the image-based region changes between two moments, as a
  share of what the volume region changes.

Each figure is set against its limit from the far-field issue; the JSON lists every case, the
contact sheet shows every LOD frame with its name."""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from app.scenes import SCENES, get_scene
from core.camera import Camera
from core.document import Document
from core.image_diff import to_float
from core.params import PRESETS
from core.quality import (
    bare_blocks,
    level_steps,
    line_gaps,
    screen_path,
    stripe_contrast,
    technique_regions,
)

MAGENTA = (1.0, 0.0, 1.0)
DEM_SCALE = 6.0  # world units for white of the stand-in DEM (docs/far-field.md)
REFERENCE_BUDGET_S = 40.0  # an all-geometry frame expected to take longer is not drawn
# the patch extremes the panel allows, on top of the meadow's main grass
EXTREMES: dict[str, dict] = {
    "upright": {"tilt_min": 0.0, "tilt_max": 0.0},
    "long": {"length_min": 0.5, "length_max": 0.9, "patch_height": 0.95},
    "wide": {"width_min": 0.04, "width_max": 0.06},
    "dense": {"blade_count": 5000},
    "sparse": {"blade_count": 400},
}
LIMITS = {
    "bare_blocks": 0.01,  # landscape: density 1 everywhere
    "steps_p95": 2.0,  # football: across a boundary ≤ 2× inside a level
    "region_colour": 0.03,  # meadow, bench: each representation's region mean colour
    "steps_over_reference": 1.5,  # meadow, bench: across the same blocks as all-geometry
    "wind_image_share": 1.0 / 3.0,  # the image-based region moves ≥ a third of the volume's
    "touchline_gaps": 0.1,  # football: a touchline's points in gaps, where it shows
    "stripe_contrast": 1.5,  # the DEM: pattern at stripes' scale over all-geometry's
}


@dataclass
class Case:
    name: str
    scene: str
    camera: str
    params: dict = field(default_factory=dict)  # changes to the first grass type's patch
    preset: str | None = None
    dem: bool = False  # the scene on a steep stand-in DEM, as `sward new --height-map` loads it

    def document(self) -> Document:
        document = get_scene(self.scene).document()
        if self.dem:
            from core.heights import ridged_hills
            from core.map_io import resample

            heights = np.rint(ridged_hills(512) * 65535) / 65535  # a 16-bit file's steps
            document.set_heights(resample(heights[..., None], document.maps.size), DEM_SCALE)
        params = document.params(0)
        if self.preset is not None:
            params = PRESETS[self.preset].replace(seed=params.seed)
        if self.params:
            params = params.replace(**self.params)
        if params != document.params(0):
            document.set_params(0, params)
        return document


def cases() -> list[Case]:
    """Every built-in scene at every camera, the meadow on a steep stand-in DEM, then the
    meadow's presets and extremes at its default and path cameras."""
    out = [
        Case(f"{name}/{camera}", name, camera)
        for name, scene in SCENES.items()
        for camera in scene.cameras
    ]
    out += [Case(f"dem/{camera}", "meadow", camera, dem=True) for camera in ("default", "path")]
    for camera in ("default", "path"):
        for preset in PRESETS:
            slug = preset.replace(" ", "-")
            out.append(Case(f"meadow/{camera}/preset:{slug}", "meadow", camera, preset=preset))
        for extreme, changes in EXTREMES.items():
            out.append(Case(f"meadow/{camera}/{extreme}", "meadow", camera, params=changes))
    return out


def region_colours(lod: np.ndarray, reference: np.ndarray, regions: dict) -> dict:
    """Per representation, the length of the difference of the mean RGB (0 … 1) of its region
    in the LOD frame and in the reference."""
    a, b = to_float(lod), to_float(reference)
    out = {}
    for name, mask in regions.items():
        if mask.sum() >= 64:
            out[name] = float(np.linalg.norm(a[mask].mean(axis=0) - b[mask].mean(axis=0)))
    return out


class _Frames:
    """The frames a case needs, from one renderer (LOD, and all-geometry through it)."""

    def __init__(self, document: Document, size: tuple[int, int]) -> None:
        from app.quality import QualityRun

        self.run = QualityRun(document, size, REFERENCE_BUDGET_S)
        self.size = size

    def lod(self, camera: Camera, view: str = "shaded", soil=None) -> np.ndarray:
        pipeline = self.run.lod.pipeline
        kept = pipeline.ground.under_grass
        pipeline.view = view
        if soil is not None:
            pipeline.ground.under_grass = soil
        try:
            return self.run.lod.render(camera, self.size, measure=False)[0]
        finally:
            pipeline.view = "shaded"
            pipeline.ground.under_grass = kept

    def release(self) -> None:
        self.run.release()


def case_figures(case: Case, size: tuple[int, int], wind: bool) -> tuple[dict, np.ndarray]:
    from render.grass_type import technique_colors

    document = case.document()
    camera = document.camera(case.camera)
    frames = _Frames(document, size)
    row: dict = {"case": case.name}
    try:
        start = time.perf_counter()
        frames.run.lod_frame(camera)  # slices convert, shaders compile
        shaded = frames.lod(camera)
        techniques = frames.lod(camera, "techniques")
        row.update(bare_blocks(shaded, frames.lod(camera, soil=MAGENTA), techniques))
        by_level = technique_colors()
        colors = [c for name in ("geometry", "volume", "image") for c in by_level[name]]
        triangles, estimate = frames.run.reference_estimate_s(camera)
        reference = None
        if estimate <= REFERENCE_BUDGET_S:
            reference, _ = frames.run.geometry(camera)
            regions = technique_regions(shaded, techniques, by_level)
            row["region_colour"] = region_colours(shaded, reference, regions)
            row["stripes"] = {
                name: stripe_contrast(shaded, reference, mask) for name, mask in regions.items()
            }
        else:
            row["reference"] = f"not drawn: {triangles:,} triangles, ~{estimate:.0f} s"
        steps = level_steps(shaded, techniques, colors, reference)
        row["steps"] = steps
        if case.scene == "football":
            row["touchlines"] = _touchline_gaps(shaded, camera, get_scene(case.scene).grid)
        if wind and reference is not None:
            row["wind"] = _wind_figures(frames, document, camera, by_level)
        row["seconds"] = time.perf_counter() - start
    finally:
        frames.release()
    row["checks"] = _checks(case, row)
    return row, shaded


def _touchline_gaps(frame: np.ndarray, camera: Camera, grid: tuple[int, int]) -> list[dict]:
    """Per touchline of the football, its continuity in the frame (core/quality.py)."""
    from core.markings import touchlines

    h, w = frame.shape[:2]
    view_proj = camera.projection(w / h) @ camera.view()
    out = []
    for line in touchlines(*grid):
        points, across = screen_path(line, view_proj, (w, h))
        out.append(
            line_gaps(frame, points, across) if len(points) else {"samples": 0, "gaps": None}
        )
    return out


def _wind_figures(frames, document, camera, by_level) -> dict:
    """The mean change of each representation's region between the wind's moments 0 and
    0.5 s, and the image-based region's change over the volume region's. The regions are
    those of the frames under the wind: while it blows, the blades reach farther out."""
    document.wind = document.wind.replace(enabled=True)
    frames.run.set_time(0.0)
    moments = [to_float(frames.lod(camera))]
    regions = technique_regions(moments[0], frames.lod(camera, "techniques"), by_level)
    frames.run.set_time(0.5)
    moments.append(to_float(frames.lod(camera)))
    change = np.abs(moments[1] - moments[0]).mean(axis=-1)
    out = {name: float(change[mask].mean()) for name, mask in regions.items() if mask.sum() >= 64}
    if "image" in out and out.get("volume"):
        out["image_over_volume"] = out["image"] / max(out["volume"], 1e-9)
    return out


def _checks(case: Case, row: dict) -> dict:
    """Each limit that applies to the case: its figure and whether it holds."""
    checks: dict = {}

    def check(name: str, value, limit: float) -> None:
        if value is not None:
            checks[name] = {"value": value, "limit": limit, "holds": bool(value <= limit)}

    if case.scene == "landscape":
        check("bare_blocks", row["bare_blocks"], LIMITS["bare_blocks"])
    steps = row.get("steps", {})
    if case.scene == "football":
        check("steps_p95", steps.get("p95_across_over_inside"), LIMITS["steps_p95"])
        gaps = [line["gaps"] for line in row.get("touchlines", []) if line["gaps"] is not None]
        check("touchline_gaps", max(gaps) if gaps else None, LIMITS["touchline_gaps"])
    if case.scene in ("meadow", "bench"):  # the DEM cases too: the meadow on other ground
        for name, value in row.get("region_colour", {}).items():
            check(f"region_colour_{name}", value, LIMITS["region_colour"])
        check(
            "steps_over_reference", steps.get("across_over_reference"),
            LIMITS["steps_over_reference"],
        )  # fmt: skip
    if case.dem:
        stripes = row.get("stripes", {})
        for name in ("volume", "image"):
            check(f"stripe_contrast_{name}", stripes.get(name), LIMITS["stripe_contrast"])
    share = row.get("wind", {}).get("image_over_volume")
    if share is not None:
        # at least a third: the check holds where the share reaches it
        checks["wind_image_share"] = {
            "value": share,
            "limit": LIMITS["wind_image_share"],
            "holds": bool(share >= LIMITS["wind_image_share"]),
        }
    return checks


def contact_sheet(frames: list[tuple[str, np.ndarray]], columns: int = 4) -> np.ndarray:
    """The frames in a grid at half size, each with its case's name above it."""
    from PIL import Image, ImageDraw

    h, w = frames[0][1].shape[0] // 2, frames[0][1].shape[1] // 2
    label = 14
    rows = (len(frames) + columns - 1) // columns
    sheet = Image.new("RGB", (columns * w, rows * (h + label)), (24, 24, 24))
    draw = ImageDraw.Draw(sheet)
    for i, (name, image) in enumerate(frames):
        x, y = (i % columns) * w, (i // columns) * (h + label)
        sheet.paste(Image.fromarray(image).resize((w, h)), (x, y + label))
        draw.text((x + 3, y + 1), name, fill=(230, 230, 230))
    return np.asarray(sheet)


def sweep(
    size: tuple[int, int], out: Path | None, only: list[str] | None = None
) -> tuple[str, dict]:
    """Every case (or those whose name starts with one of `only`); the printed table and the
    JSON document."""
    rows, frames = [], []
    for case in cases():
        if only and not any(case.name.startswith(prefix) for prefix in only):
            continue
        wind = case.name == "meadow/default"
        row, image = case_figures(case, size, wind)
        rows.append(row)
        frames.append((case.name, image))
    result = {"size": list(size), "limits": LIMITS, "cases": rows}
    failed = [
        f"{row['case']}: {name} {check['value']:.3f} (limit {check['limit']:g})"
        for row in rows
        for name, check in row["checks"].items()
        if not check["holds"]
    ]
    result["failed"] = failed
    text = report(result)
    if out is not None:
        from PIL import Image

        out.mkdir(parents=True, exist_ok=True)
        (out / "sweep.json").write_text(json.dumps(result, indent=2) + "\n")
        if frames:
            Image.fromarray(contact_sheet(frames)).save(out / "sweep.png")
        text += f"\nwrote {out / 'sweep.json'} and the contact sheet {out / 'sweep.png'}"
    return text, result


def report(result: dict) -> str:
    lines = [f"far-field sweep at {result['size'][0]}x{result['size'][1]}"]
    for row in result["cases"]:
        steps = row.get("steps", {})
        parts = [f"{row['case']:40s}", f"bare {row['bare_blocks']:.3f}"]
        if steps.get("p95_across_over_inside") is not None:
            parts.append(f"steps p95 {steps['p95_across_over_inside']:.2f}x inside")
        if steps.get("across_over_reference") is not None:
            parts.append(f"{steps['across_over_reference']:.2f}x geometry's")
        colours = row.get("region_colour", {})
        if colours:
            parts.append(
                "colour " + " ".join(f"{name[0]} {value:.3f}" for name, value in colours.items())
            )
        stripes = {k: v for k, v in row.get("stripes", {}).items() if v is not None}
        if stripes:
            parts.append("stripes " + " ".join(f"{k[0]} {v:.2f}" for k, v in stripes.items()))
        if row.get("touchlines"):
            gaps = [line["gaps"] for line in row["touchlines"]]
            parts.append(
                "touchline gaps " + " ".join("–" if g is None else f"{g:.2f}" for g in gaps)
            )
        if "wind" in row and "image_over_volume" in row["wind"]:
            parts.append(f"wind image/volume {row['wind']['image_over_volume']:.2f}")
        lines.append("  ".join(parts))
    failed = result["failed"]
    lines.append(f"{len(failed)} checks over their limits" + (":" if failed else ""))
    lines.extend(f"  {line}" for line in failed)
    return "\n".join(lines)
