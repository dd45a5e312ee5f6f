"""`sward tune`: search the LOD settings for the front of frame cost against quality (thesis
ch. 8's adaptive rendering, as an assistant): within a frame budget the best quality, or for a
quality target the cheapest frame. core/tuning.py has the knobs, the front and the choice.

Views: each camera with the same moved on DOLLY_FRAMES - 1 times by a quarter of a cell (so the
zone boundaries sweep over the ground as when a person walks), or a path's frames.

Quality: quarter-resolution FLIP of each candidate's frames against all-geometry, over the
frame and over each technique region of the shipped setting's frame (the same pixels for every
candidate), and popping over each view's frames (the largest change from one frame to the next
over the reference's: narrow transitions look better standing still and pop when moving). The
references are drawn once and kept on disk (render/reference_cache.py).

Cost: per view the median frame time of its frames (after one unmeasured frame, in which a new
slice count converts), averaged over the views. A CPU renderer's speed drifts by some percent
over minutes, so claims are measured again at the end, in turns with the shipped setting
(VERIFY_ROUNDS each), and those medians are what the verdict compares."""

from __future__ import annotations

import json
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from app.tune_report import plot_front, report
from core.camera import Camera
from core.document import Document
from core.image_diff import QUARTER, flip
from core.quality import popping, quarter_mask, technique_regions
from core.tuning import (
    SHIPPED,
    Candidate,
    Knobs,
    as_good_as_shipped,
    choose,
    first_candidates,
    front,
    nearest_miss,
    popping_limit,
    proposals,
    ranked,
    tuned,
)

DOLLY_FRAMES = 4  # a camera's frames: it and the same moved on, for cost and popping
DOLLY_STEP = 0.25  # world units (a quarter of a cell) a frame
VERIFY_ROUNDS = 5
VERIFY_AT_MOST = 6  # candidates measured again in turns for one claim
NOISE = 1.1  # the search's times may be this far off: candidates up to it are measured again
MAX_CANDIDATES = 150
BATCH = 6  # proposals nearest the current choice tried before proposing again
TIME_LIMIT_S = 10 * 60.0  # the search stops proposing after this long


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

    def release(self) -> None:
        self.document.set_lods(self.shipped)
        self.renderer.release()
        self.ctx.release()

    # -- what every candidate is compared with -------------------------------------------------
    def prepare(self) -> None:
        for name, cameras in self.views:
            self.say(f"references of {name}: {len(cameras)} frames")
            refs, masks = [], []
            for camera in cameras:
                image, mask = self._reference(camera)
                refs.append(image)
                masks.append(mask)
            self.references.append(refs)
            self.masks.append(masks)

    def _reference(self, camera: Camera) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        from render.comparison import drawn_as
        from render.grass_type import technique_colors
        from render.reference_cache import geometry_frame

        image, drawn = geometry_frame(self.renderer, camera, self.size)
        self.drawn += drawn
        self.reused += not drawn
        shaded, _ = self.renderer.render(camera, self.size, measure=False)
        with drawn_as(self.renderer.pipeline, view="techniques"):
            techniques, _ = self.renderer.render(camera, self.size, measure=False)
        regions = technique_regions(shaded, techniques, technique_colors())
        return image, {n: quarter_mask(m) for n, m in regions.items() if m.any()}

    # -- one candidate ---------------------------------------------------------------------------
    def frames(self, knobs: Knobs) -> tuple[list[float], list[list[np.ndarray]], dict]:
        """Per view the median frame time (ms) and its frames, and the mean counts."""
        lods = [tuned(lod, knobs) for lod in self.shipped]
        self.document.set_lods(lods)  # type: ignore[arg-type]
        costs, images = [], []
        counts = {"c_g": 0, "c_v": 0, "c_i": 0, "triangles": 0}
        drawn = 0
        for _name, cameras in self.views:
            self.renderer.render(cameras[0], self.size, measure=False)  # new slices convert
            times, seq = [], []
            for camera in cameras:
                image, stats = self.renderer.render(camera, self.size, measure=True)
                times.append(stats.t_a_ms)
                seq.append(image)
                for k in counts:
                    counts[k] += getattr(stats, k)
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


def tune(
    document: Document,
    size: tuple[int, int],
    views: list[tuple[str, list[Camera]]],
    path: str | None,
    budget_ms: float | None,
    quality: float | None,
    out: Path | None,
    max_candidates: int = MAX_CANDIDATES,
    time_limit_s: float = TIME_LIMIT_S,
    say: Callable[[str], None] | None = None,
) -> tuple[str, dict]:
    """Search; the printed report and the JSON document. Ctrl+C stops the search and keeps
    what it found."""
    say = say or (lambda text: print(text, file=sys.stderr, flush=True))
    started = time.monotonic()
    run = TuneRun(document, size, views, say)
    candidates: list[Candidate] = []
    seen: set[Knobs] = set()
    stopped = ""
    try:
        prepared = time.monotonic()
        run.prepare()
        references_s = time.monotonic() - prepared
        run.evaluate(SHIPPED)  # the first frames after the references run slow: warm up
        shipped = run.evaluate(SHIPPED)
        assert shipped is not None
        candidates.append(shipped)
        seen.add(SHIPPED)
        if budget_ms is None and quality is None:
            budget_ms = shipped.cost_ms
        say(
            f"shipped setting: {shipped.cost_ms:.0f} ms, FLIP {shipped.flip:.4f}"
            + (f", popping {shipped.popping:.2f}" if shipped.popping is not None else "")
        )
        queue = [k for k in first_candidates() if k not in seen]
        try:
            while queue and len(seen) < max_candidates:
                if time.monotonic() - started > time_limit_s:
                    stopped = f"time limit {time_limit_s:.0f} s"
                    break
                knobs = queue.pop(0)
                seen.add(knobs)
                found = run.evaluate(knobs)
                if found is not None:
                    candidates.append(found)
                    say(
                        f"[{len(seen)}/{max_candidates}] {knobs.label()}: "
                        f"{found.cost_ms:.0f} ms, FLIP {found.flip:.4f}"
                    )
                if not queue:
                    target = choose(
                        candidates, budget_ms, quality, popping_limit(shipped)
                    ) or nearest_miss(candidates, budget_ms, quality)
                    queue = proposals(candidates, seen, target)[:BATCH]
        except KeyboardInterrupt:
            stopped = "stopped (Ctrl+C)"
            say("stopped: keeping what was found")
        result = _result(run, document, size, views, path, budget_ms, quality, candidates, shipped)
        result["stopped"] = stopped or ("no more proposals" if not queue else "candidate limit")
    finally:
        run.release()
    result["elapsed_s"] = time.monotonic() - started
    result["references_s"] = references_s
    text = report(result)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "tune.json").write_text(json.dumps(result, indent=2) + "\n")
        plot_front(result, out / "front.png")
        text += f"\nwrote {out / 'tune.json'} and {out / 'front.png'}"
    return text, result


def _result(run, document, size, views, path, budget_ms, quality, candidates, shipped) -> dict:
    checks = Checks(run, shipped, budget_ms)
    chosen = _chosen(candidates, budget_ms, quality, checks, popping_limit(shipped))
    result: dict = {
        "scene": document.name,
        "size": list(size),
        "views": [name for name, _ in views],
        "frames_per_view": [len(cameras) for _, cameras in views],
        "path": path,
        "budget_ms": budget_ms,
        "quality": quality,
        "references_reused": run.reused,
        "references_drawn": run.drawn,
        "shipped": shipped.to_dict(),
        "candidates": [c.to_dict() for c in candidates],
        "front": [candidates.index(c) for c in front(candidates)],
        "chosen": None if chosen is None else candidates.index(chosen),
    }
    if budget_ms is not None and budget_ms >= shipped.cost_ms:
        # the chosen setting where it beats the shipped one in every figure, else the cheapest
        # that does (each measured again in turns)
        pool = as_good_as_shipped(candidates, shipped, budget_ms * NOISE)
        if chosen in pool:
            pool = [chosen, *(c for c in pool if c is not chosen)]
        better = next((c for c in pool[:VERIFY_AT_MOST] if checks.holds(c)), None)
        result["better_than_shipped"] = None if better is None else candidates.index(better)
        if better is None:
            cheaper = [c for c in candidates if c.cost_ms < shipped.cost_ms]
            result["verdict"] = (
                f"the shipped setting is on the front: none of the {len(cheaper)} cheaper "
                "settings tried is as good in the frame and every region"
                + (" at no more cost measured in turns" if checks.done else "")
            )
    index = {c.knobs: i for i, c in enumerate(candidates)}
    result["verified"] = [{"candidate": index[k], **v} for k, v in checks.done.items()]
    if chosen is not None:
        lods = [tuned(lod, chosen.knobs) for lod in run.shipped]
        result["chosen_lods"] = [_levels(lod) for lod in lods]
    return result


class Checks:
    """Candidates measured again in turns with the shipped setting: a candidate holds the
    budget when its median is within the budget as the machine runs now (the budget scaled by
    how the shipped setting's time moved since the search measured it)."""

    def __init__(self, run: TuneRun, shipped: Candidate, budget_ms: float | None) -> None:
        self.run, self.shipped, self.budget_ms = run, shipped, budget_ms
        self.done: dict[Knobs, dict] = {}

    def holds(self, c: Candidate) -> bool:
        if c.knobs == SHIPPED:
            return self.budget_ms is None or c.cost_ms <= self.budget_ms
        if c.knobs not in self.done:
            shipped_ms, ms = self.run.in_turns(SHIPPED, c.knobs, VERIFY_ROUNDS)
            allowed = (self.budget_ms or c.cost_ms) * shipped_ms / self.shipped.cost_ms
            self.done[c.knobs] = {
                "shipped_ms": shipped_ms,
                "ms": ms,
                "allowed_ms": allowed,
                "rounds": VERIFY_ROUNDS,
                "holds": ms <= allowed,
            }
            self.run.say(
                f"measured in turns: {c.knobs.label()} {ms:.0f} ms, shipped {shipped_ms:.0f} "
                f"ms, allowed {allowed:.0f} ms"
            )
        return self.done[c.knobs]["holds"]


def _chosen(candidates, budget_ms, quality, checks: Checks, pops) -> Candidate | None:
    """For a quality: the cheapest that reaches it. For a budget: the best whose time holds
    the budget measured again in turns (the first VERIFY_AT_MOST tried); when none does, the
    best by the search's figures (its entry in "verified" says so). Either popping no more
    than `pops`."""
    if budget_ms is None:
        return choose(candidates, quality=quality, popping_limit=pops)
    within = ranked(candidates, budget_ms, popping_limit=pops)
    nearly = [
        c for c in ranked(candidates, budget_ms * NOISE, popping_limit=pops) if c not in within
    ]
    for c in (within + nearly)[:VERIFY_AT_MOST]:  # within the budget by the search's times first
        if checks.holds(c):
            return c
    return choose(candidates, budget_ms, popping_limit=pops)


def _levels(config) -> list[dict]:
    return [
        {
            "representation": lv.representation,
            "begin": round(lv.begin, 4),
            "end": None if lv.end is None else round(lv.end, 4),
            "slices": lv.slices,
            "macro": lv.macro,
        }
        for lv in config.levels
    ]
