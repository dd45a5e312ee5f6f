"""The renders of `sward tune` (app/tune.py): one renderer on one context, per view a sequence
of cameras, their all-geometry references and the shipped setting's technique regions, and a
candidate's frames, time and quality against them. The search runs one here, and each worker
of --workers / --ray runs one too (app/tune_workers.py).

Quality: quarter-resolution FLIP of each candidate's frames against all-geometry, over the
frame and over each technique region of the shipped setting's frame (the same pixels for every
candidate), and popping over each view's frames (the largest change from one frame to the next
over the reference's). Cost: per view the median frame time of its frames (after one
unmeasured frame, in which a new slice count converts), averaged over the views."""

from __future__ import annotations

import statistics
from collections.abc import Callable

import numpy as np

from app.tune_workers import Pool, TuneWorker
from core.camera import Camera
from core.document import Document
from core.image_diff import QUARTER, flip
from core.quality import popping, quarter_mask, technique_regions
from core.tuning import Candidate, Knobs, tuned

DOLLY_FRAMES = 4  # a camera's frames: it and the same moved on, for cost and popping
DOLLY_STEP = 0.25  # world units (a quarter of a cell) a frame


def dolly(camera: Camera, frames: int = DOLLY_FRAMES, step: float = DOLLY_STEP) -> list[Camera]:
    """The camera and the same moved towards its target `step` world units a frame, eye and
    target alike: the zone boundaries sweep over the ground as when a person walks."""
    eye, target = np.asarray(camera.eye), np.asarray(camera.target)
    ahead = target - eye
    ahead[1] = 0.0  # along the ground
    ahead /= max(float(np.linalg.norm(ahead)), 1e-9)
    return [
        Camera.from_eye_target(
            eye + k * step * ahead,
            target + k * step * ahead,
            fov_y=camera.fov_y,
            near=camera.near,
            far=camera.far,
        )
        for k in range(frames)
    ]


class TuneRun:
    """One renderer on one context; per view a sequence of cameras (a camera's dolly, or a
    path's frames), their references and the shipped setting's regions."""

    def __init__(
        self,
        document: Document,
        size: tuple[int, int],
        views: list[tuple[str, list[Camera]]],
        say: Callable[[str], None],
    ) -> None:
        from render.context import standalone
        from render.headless import HeadlessRenderer

        self.document, self.size, self.views, self.say = document, size, views, say
        self.ctx = standalone()
        self.renderer = HeadlessRenderer(document, self.ctx)
        self.shipped = document.lods
        self.references: list[list[np.ndarray]] = []
        self.masks: list[list[dict[str, np.ndarray]]] = []
        self.reused = self.drawn = 0

    def setup(self) -> tuple:
        """What a worker needs to draw as this run does (app/tune_workers.py)."""
        from core.project_file import document_data

        return document_data(self.document), self.document.maps.stack, self.size, self.views

    def release(self) -> None:
        self.document.set_lods(self.shipped)
        self.renderer.release()
        self.ctx.release()

    # -- what every candidate is compared with -------------------------------------------------
    def prepare(self, pool: Pool | None = None) -> None:
        """Each view's references (kept ones read, the others drawn, by the pool's workers
        when there is one) and the shipped setting's regions."""
        from render import reference_cache

        cameras = [c for _, seq in self.views for c in seq]
        names = [reference_cache.key(self.document, c, self.size, self._time()) for c in cameras]
        kept = [reference_cache.load(n, self.size) for n in names]
        for name, seq in self.views:
            self.say(f"references of {name}: {len(seq)} frames")
        drawn, regions = list(kept), [{}] * len(cameras)
        items = [(c, k is None) for c, k in zip(cameras, kept, strict=True)]
        answers = (
            enumerate(self.view(*item) for item in items)
            if pool is None
            else pool.map(TuneWorker.view, items)
        )
        for done, (i, (image, mask)) in enumerate(answers, 1):
            if image is not None:
                reference_cache.save(names[i], image)
                drawn[i] = image
            regions[i] = mask
            if pool is not None:
                self.say(f"views drawn: {done}/{len(cameras)}")
        self.drawn += sum(k is None for k in kept)
        self.reused += sum(k is not None for k in kept)
        i = 0
        for _, seq in self.views:
            self.references.append(drawn[i : i + len(seq)])
            self.masks.append(regions[i : i + len(seq)])
            i += len(seq)

    def _time(self) -> float:
        return self.renderer.pipeline.time

    def view(self, camera: Camera, reference: bool) -> tuple[np.ndarray | None, dict]:
        """The all-geometry frame at this camera, drawn now (when asked for; the search keeps
        it where it runs), and the shipped setting's regions there."""
        from render.reference_cache import draw

        image = draw(self.renderer, camera, self.size) if reference else None
        return image, self.regions(camera)

    def regions(self, camera: Camera) -> dict[str, np.ndarray]:
        """The shipped setting's technique regions at this camera, at quarter resolution."""
        from render.comparison import drawn_as
        from render.grass_type import technique_colors

        shaded, _ = self.renderer.render(camera, self.size, measure=False)
        with drawn_as(self.renderer.pipeline, view="techniques"):
            techniques, _ = self.renderer.render(camera, self.size, measure=False)
        regions = technique_regions(shaded, techniques, technique_colors())
        return {n: quarter_mask(m) for n, m in regions.items() if m.any()}

    # -- one candidate ---------------------------------------------------------------------------
    def frames(self, knobs: Knobs) -> tuple[list[float], list[list[np.ndarray]], dict]:
        """Per view the median frame time (ms) and its frames, and the mean counts."""
        lods = [tuned(lod, knobs) for lod in self.shipped]
        self.document.set_lods(lods)  # type: ignore[arg-type]
        costs, images = [], []
        counts = {"c_g": 0, "c_v": 0, "c_i": 0, "triangles": 0, "volume_slices": 0}
        drawn = 0
        for _name, cameras in self.views:
            self.renderer.render(cameras[0], self.size, measure=False)  # new slices convert
            times, seq = [], []
            for camera in cameras:
                image, stats = self.renderer.render(camera, self.size, measure=True)
                times.append(stats.t_a_ms)
                seq.append(image)
                for k in ("c_g", "c_v", "c_i", "triangles"):
                    counts[k] += getattr(stats, k)
                counts["volume_slices"] += sum(
                    n * slices for _, rep, slices, n in stats.levels if rep == "volume"
                )
                drawn += 1
            costs.append(statistics.median(times))
            images.append(seq)
        return costs, images, {k: v // max(drawn, 1) for k, v in counts.items()}

    def evaluate(self, knobs: Knobs) -> Candidate | None:
        if any(tuned(lod, knobs) is None for lod in self.shipped):
            return None
        costs, images, counts = self.frames(knobs)
        flips, regions, pops = [], {}, []
        for seq, refs, masks in zip(images, self.references, self.masks, strict=True):
            for image, reference, mask in zip(seq, refs, masks, strict=True):
                mean, error = flip(reference, image, QUARTER)
                error = error.reshape(error.shape[0], error.shape[1])
                flips.append(mean)
                for name, m in mask.items():
                    inside = error[m[: error.shape[0], : error.shape[1]]]
                    regions.setdefault(name, []).append(float(inside.mean()))
            if len(seq) > 1:
                pops.append(popping(seq, refs)["popping"])
        return Candidate(
            knobs,
            float(np.mean(costs)),
            float(np.mean(flips)),
            {n: float(np.mean(v)) for n, v in regions.items()},
            max(pops) if pops else None,
            counts,
        )

    def in_turns(self, a: Knobs, b: Knobs, rounds: int) -> tuple[float, float]:
        """Both settings' frame times measured in turns: the medians (ms)."""
        times: dict[Knobs, list[float]] = {a: [], b: []}
        for _ in range(rounds):
            for k in (a, b):
                costs, _, _ = self.frames(k)
                times[k].append(float(np.mean(costs)))
        return statistics.median(times[a]), statistics.median(times[b])
