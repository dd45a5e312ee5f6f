"""`sward quality`: the LOD frame against an all-geometry reference at each camera, or along a
camera path (core/quality.py has the figures). Per camera: FLIP at full and quarter resolution,
the 8 × 8 block colour difference, the floor (two reference frames a blade's width apart), the
figure over each technique's screen region and its ratio to the floor there, and the speed-up of
LOD over all-geometry; along a path, popping. Writes JSON and heat maps (--out DIR).

An all-geometry reference can take far longer than the LOD frame (the football player camera's
2.9 G blade triangles did not finish in 25 minutes on llvmpipe: benchmarks/lod_speedup.py). Its
triangles are counted from the query first; when drawing them would take longer than the budget
at the geometry speed the LOD frame showed, the reference is not drawn and the speed-up is
estimated. The estimate is a lower bound: a few thousand instances draw faster per triangle than
billions do."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from core.camera import Camera
from core.document import Document
from core.quality import Comparison, popping

BUDGET_S = 120.0  # longest an all-geometry reference frame may be expected to take
TRIANGLES_PER_S = 5e6  # llvmpipe's blade throughput (DESIGN.md) when a frame draws no geometry


def shifted(camera: Camera, distance: float) -> Camera:
    """The camera moved sideways by `distance` (eye and target alike)."""
    right = camera.view()[0, :3].astype(np.float64)
    eye, target = np.asarray(camera.eye), np.asarray(camera.target)
    return Camera.from_eye_target(
        eye + distance * right,
        target + distance * right,
        fov_y=camera.fov_y,
        near=camera.near,
        far=camera.far,
    )


class QualityRun:
    """The renderer one `sward quality` run needs, on one context: the LOD frame, and through
    render/comparison.py the same pipeline in the technique colours and as all-geometry."""

    def __init__(self, document: Document, size: tuple[int, int], budget_s: float) -> None:
        from render.context import standalone
        from render.headless import HeadlessRenderer

        self.size = size
        self.budget_s = budget_s
        self.ctx = standalone()
        self.lod = HeadlessRenderer(document, self.ctx)
        self.document = document
        self.blade_width = float(document.params(0).width_max)
        self._throughput: float | None = None  # triangles per second measured in LOD frames

    def set_time(self, seconds: float) -> None:
        """The moment of the wind the frames draw."""
        self.lod.pipeline.time = seconds

    def release(self) -> None:
        self.lod.release()
        self.ctx.release()

    def lod_frame(self, camera: Camera):
        self.lod.render(camera, self.size, measure=False)  # shaders compile, slices convert
        image, stats = self.lod.render(camera, self.size, measure=True)
        if stats.triangles and stats.t_g_ms > 0:
            self._throughput = stats.triangles / (stats.t_g_ms / 1000.0)
        return image, stats

    def geometry(self, camera: Camera, measure: bool = False):
        """An all-geometry frame (image, statistics)."""
        from core.view_mode import ViewMode
        from render.comparison import drawn_as

        with drawn_as(self.lod.pipeline, ViewMode.GEOMETRY):
            return self.lod.render(camera, self.size, measure=measure)

    def reference_estimate_s(self, camera: Camera) -> tuple[int, float]:
        triangles = self.lod.pipeline.geometry_triangles(camera, self.size, "geometry")
        return triangles, triangles / (self._throughput or TRIANGLES_PER_S)

    def compare(self, camera: Camera, lod):
        """The LOD frame (image, statistics) against all-geometry (render/comparison.py)."""
        from render.comparison import lod_against_geometry

        fbo = self.lod._target(self.size)
        return lod_against_geometry(self.lod.pipeline, camera, fbo, self.size, lod=lod)

    def camera_figures(self, name: str, camera: Camera, out: Path | None) -> dict:
        lod_image, lod_stats = self.lod_frame(camera)
        row: dict = {"camera": name, "lod_ms": lod_stats.t_a_ms}
        triangles, estimate = self.reference_estimate_s(camera)
        row["reference_triangles"] = triangles
        if estimate > self.budget_s:
            row["reference"] = (
                f"not drawn: {triangles:,} blade triangles, estimated {estimate:.3g} s "
                f"(budget {self.budget_s:g} s)"
            )
            row["speedup_estimated"] = estimate * 1000.0 / max(lod_stats.t_a_ms, 1e-3)
            return row
        compared = self.compare(camera, (lod_image, lod_stats))
        reference, lod, regions = compared.reference, compared.comparison, compared.regions
        floor_image, _ = self.geometry(shifted(camera, self.blade_width))
        floor = Comparison.of(reference, floor_image)
        row.update(
            compared.found,
            floor=floor.to_dict(),
            over_floor=lod.flip_quarter / max(floor.flip_quarter, 1e-9),
        )
        for technique, region in regions.items():
            here, base = row["techniques"][technique]["flip_quarter"], floor.region(region)
            row["techniques"][technique].update(
                floor=base, over_floor=None if here is None or not base else here / base
            )
        if self.document.wind.enabled:
            self._still_floor(row, camera, regions)
        if out is not None:
            from PIL import Image

            stem = out / name
            Image.fromarray(lod_image).save(f"{stem}-lod.png")
            Image.fromarray(reference).save(f"{stem}-geometry.png")
            Image.fromarray(compared.heat_map()).save(f"{stem}-flip.png")
            row["heat_map"] = f"{stem}-flip.png"
        return row

    def _still_floor(self, row: dict, camera: Camera, regions: dict) -> None:
        """With the wind on, the floor of still air as well (two more all-geometry frames):
        bent blades show less detail, so the wind's own floor is lower, and "as in still air"
        compares the LOD frame's difference with the yardstick still air had."""
        document = self.document
        wind = document.wind
        document.wind = wind.replace(enabled=False)
        try:
            reference, _ = self.geometry(camera)
            shifted_image, _ = self.geometry(shifted(camera, self.blade_width))
        finally:
            document.wind = wind
        still = Comparison.of(reference, shifted_image)
        row["still_floor"] = still.to_dict()
        row["over_still_floor"] = row["lod"]["flip_quarter"] / max(still.flip_quarter, 1e-9)
        for technique, region in regions.items():
            here, base = row["techniques"][technique]["flip_quarter"], still.region(region)
            row["techniques"][technique].update(
                still_floor=base,
                over_still_floor=None if here is None or not base else here / base,
            )

    def path_figures(
        self, name: str, cameras: list[Camera], start: float = 0.0, step: float = 0.0
    ) -> dict:
        """Along the path's cameras, frame i at the wind's moment start + i · step."""
        lod_frames, references = [], []
        for index, camera in enumerate(cameras):
            self.set_time(start + index * step)
            lod_frames.append(self.lod_frame(camera)[0])
            triangles, estimate = self.reference_estimate_s(camera)
            if estimate > self.budget_s:
                return {
                    "path": name,
                    "reference": f"not drawn: {triangles:,} blade triangles at a path frame, "
                    f"estimated {estimate:.3g} s (budget {self.budget_s:g} s)",
                }
            references.append(self.geometry(camera)[0])
        flips = [
            Comparison.of(r, x).flip_quarter for r, x in zip(references, lod_frames, strict=True)
        ]
        return {
            "path": name,
            "frames": len(cameras),
            "flip_quarter_mean": float(np.mean(flips)),
            "flip_quarter_max": float(np.max(flips)),
            **popping(lod_frames, references),
        }


def quality(
    document: Document,
    size: tuple[int, int],
    cameras: list[str],
    path: str | None,
    frames: int,
    out: Path | None,
    budget_s: float = BUDGET_S,
    time: float = 0.0,
    time_step: float = 0.0,
) -> tuple[str, dict]:
    """Render and compare (at the wind's moment `time`; along a path each frame `time_step`
    later); the printed table and the JSON document."""
    run = QualityRun(document, size, budget_s)
    result: dict = {
        "scene": document.name,
        "size": list(size),
        # per grass type: the view height its LOD distances hold for (None: world units)
        "lod_view_height": [lod.view_height for lod in document.lods],
        "wind": document.wind.enabled,
        "time": time,
        "time_step": time_step,
        "cameras": [],
    }
    try:
        if path is not None:
            cameras_on_path = document.path_cameras(path, frames)
            result["path"] = run.path_figures(path, cameras_on_path, time, time_step)
        run.set_time(time)
        for name in cameras:
            result["cameras"].append(run.camera_figures(name, document.camera(name), out))
    finally:
        run.release()
    text = report(result)
    if out is not None:
        target = out / "quality.json"
        target.write_text(json.dumps(result, indent=2) + "\n")
        text += f"\nwrote {target} and heat maps in {out}"
    return text, result


def _f(value, digits: int = 3) -> str:
    return "-" if value is None else f"{value:.{digits}f}"


def report(result: dict) -> str:
    w, h = result["size"]
    heights = {v for v in result.get("lod_view_height", []) if v is not None}
    zones = f" (LOD distances for a view {', '.join(f'{v:g}' for v in sorted(heights))} px tall)"
    wind = ""
    if result.get("wind"):
        wind = f", wind at {result['time']:g} s"
        if result.get("time_step"):
            wind += f" (+{result['time_step']:g} s a path frame)"
    lines = [
        f"{result['scene']} at {w}x{h}: LOD against all-geometry{zones if heights else ''}{wind}"
    ]
    for row in result["cameras"]:
        if "lod" not in row:
            lines.append(
                f"  {row['camera']}: reference {row['reference']}; "
                f"speed-up of LOD about {row['speedup_estimated']:.0f}x"
            )
            continue
        lod, floor = row["lod"], row["floor"]
        lines.append(
            f"  {row['camera']}: FLIP {_f(lod['flip_full'])} full, {_f(lod['flip_quarter'])} "
            f"quarter (floor {_f(floor['flip_quarter'])}, {row['over_floor']:.2f}x), "
            f"block colour {_f(lod['block_color'])} (floor {_f(floor['block_color'])}), "
            f"LOD {row['lod_ms']:.0f} ms vs geometry {row['geometry_ms']:.0f} ms "
            f"({row['speedup']:.1f}x)"
        )
        if "still_floor" in row:
            lines.append(
                f"    still air's floor {_f(row['still_floor']['flip_quarter'])}: "
                f"{row['over_still_floor']:.2f}x"
            )
        for technique, t in row["techniques"].items():
            if t["pixels"]:
                still = ""
                if "still_floor" in t:
                    still = f" ({_f(t['over_still_floor'], 2)}x still air's)"
                lines.append(
                    f"    {technique:9s} {t['pixels']:7d} px  FLIP {_f(t['flip_quarter'])} "
                    f"quarter, floor {_f(t['floor'])}, {_f(t['over_floor'], 2)}x the floor"
                    f"{still}"
                )
    p = result.get("path")
    if p is not None:
        if "popping" in p:
            lines.append(
                f"  path {p['path']} ({p['frames']} frames): FLIP quarter mean "
                f"{_f(p['flip_quarter_mean'])}, max {_f(p['flip_quarter_max'])}; popping "
                f"{p['popping']:.2f} (largest change {_f(p['lod_max_change'])} against "
                f"{_f(p['reference_max_change'])})"
            )
        else:
            lines.append(f"  path {p['path']}: reference {p['reference']}")
    return "\n".join(lines)
