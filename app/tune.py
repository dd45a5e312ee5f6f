"""`sward tune`: search the LOD settings for the front of frame cost against quality (thesis
ch. 8's adaptive rendering, as an assistant): within a frame budget the best quality, or for a
quality target the cheapest frame. core/tuning.py has the knobs, the front and the choice.

Views: each camera with the same moved on by a quarter of a cell a frame (so the zone
boundaries sweep over the ground as when a person walks), or a path's frames; their renders,
references and figures are app/tune_run.py's.

Cost: measured here, one candidate at a time; with --workers / --ray the first candidates are
measured so and the others predicted from their counts (core/cost_model.py), since frames
drawn side by side time each other. A CPU renderer's speed drifts by some percent over minutes,
so claims are measured again at the end, alone, in turns with the shipped setting
(VERIFY_ROUNDS each), and those medians are what the verdict compares."""

from __future__ import annotations

import dataclasses
import json
import sys
import time
from collections.abc import Callable
from pathlib import Path

from app.tune_report import plot_front, report
from app.tune_run import TuneRun
from app.tune_workers import Pool, TuneWorker
from core.camera import Camera
from core.cost_model import CostModel
from core.document import Document
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

VERIFY_ROUNDS = 5
VERIFY_AT_MOST = 6  # candidates measured again in turns for one claim
NOISE = 1.1  # the search's times may be this far off: candidates up to it are measured again
MAX_CANDIDATES = 150
BATCH = 6  # proposals nearest the current choice tried before proposing again
TIME_LIMIT_S = 10 * 60.0  # the search stops proposing after this long


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
    workers: Callable[[tuple], Pool] | None = None,
) -> tuple[str, dict]:
    """Search; the printed report and the JSON document. Ctrl+C stops the search and keeps
    what it found. `workers` starts a pool (app/tune_workers.py) from the workers' setup: the
    references and candidates are then drawn there, and a candidate's cost is predicted from
    its counts by a model fitted to the first candidates measured here one at a time."""
    say = say or (lambda text: print(text, file=sys.stderr, flush=True))
    started = time.monotonic()
    run = TuneRun(document, size, views, say)
    search = Search(run, budget_ms, quality, max_candidates, say)
    pool = None
    stopped, references_s = "", 0.0
    try:
        if workers is not None:
            say("starting the workers")
            pool = workers(run.setup())
            search.where = pool.where
        prepared = time.monotonic()
        run.prepare(pool)
        references_s = time.monotonic() - prepared
        if pool is not None:
            pool.everyone(TuneWorker.set_references, run.references, run.masks)
        try:
            search.start()
            while search.queue and len(search.seen) < max_candidates:
                if time.monotonic() - started > time_limit_s:
                    stopped = f"time limit {time_limit_s:.0f} s"
                    break
                search.step(pool)
        except KeyboardInterrupt:
            stopped = "stopped (Ctrl+C)"
            say("stopped: keeping what was found")
        if pool is not None:  # the verification measures here, alone
            pool.close()
            pool = None
        if search.shipped is None:
            raise KeyboardInterrupt
        result = _result(run, document, size, views, path, search)
        result["stopped"] = stopped or (
            "no more proposals" if not search.queue else "candidate limit"
        )
    finally:
        if pool is not None:
            pool.close()
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


class Search:
    """The candidates found so far and the next to try. Without workers each is measured
    here; with them, the first candidates are measured here one at a time (the cost model's
    frames) and the rest drawn by the workers, their cost predicted from their counts."""

    def __init__(self, run: TuneRun, budget_ms, quality, max_candidates: int, say) -> None:
        self.run, self.budget_ms, self.quality = run, budget_ms, quality
        self.max_candidates, self.say = max_candidates, say
        self.candidates: list[Candidate] = []
        self.seen: set[Knobs] = set()
        self.tried = 0  # settings evaluated (or found invalid), the shipped one included
        self.queue: list[Knobs] = []
        self.shipped: Candidate | None = None
        self.model: CostModel | None = None
        self.where = "this process"

    def start(self) -> None:
        self.run.evaluate(SHIPPED)  # the first frames after the references run slow: warm up
        shipped = self.run.evaluate(SHIPPED)
        assert shipped is not None
        self.shipped = shipped
        self._add(SHIPPED, shipped)
        if self.budget_ms is None and self.quality is None:
            self.budget_ms = shipped.cost_ms
        self.say(
            f"shipped setting: {shipped.cost_ms:.0f} ms, FLIP {shipped.flip:.4f}"
            + (f", popping {shipped.popping:.2f}" if shipped.popping is not None else "")
        )
        self.queue = [k for k in first_candidates() if k not in self.seen]

    def step(self, pool: Pool | None) -> None:
        """Evaluate the next batch; propose more when the queue runs out."""
        if pool is None or self.model is None:  # here, one at a time
            knobs = self.queue.pop(0)
            self._add(knobs, self.run.evaluate(knobs))
            if pool is not None and not self.queue:
                measured = [c for c in self.candidates if not c.predicted]
                self.model = CostModel.fit(
                    [c.counts for c in measured], [c.cost_ms for c in measured]
                )
                self.say(
                    f"cost model from {len(measured)} settings measured here: "
                    f"{self.model.loo_error:.1%} off, each left out of its fit"
                )
        else:
            room = self.max_candidates - len(self.seen)
            batch = self.queue[: min(max(BATCH, len(pool)), room)]
            del self.queue[: len(batch)]
            self.seen.update(batch)
            for i, found in pool.map(TuneWorker.evaluate, [(k,) for k in batch]):
                if found is not None:
                    found = dataclasses.replace(
                        found, cost_ms=self.model.predict(found.counts), predicted=True
                    )
                self._add(batch[i], found)
        if not self.queue:
            target = choose(
                self.candidates, self.budget_ms, self.quality, popping_limit(self.shipped)
            ) or nearest_miss(self.candidates, self.budget_ms, self.quality)
            self.queue = proposals(self.candidates, self.seen, target)[:BATCH]

    def _add(self, knobs: Knobs, found: Candidate | None) -> None:
        self.seen.add(knobs)
        self.tried += 1
        if found is None:
            return
        self.candidates.append(found)
        if knobs != SHIPPED:
            self.say(
                f"[{self.tried}/{self.max_candidates}] {knobs.label()}: "
                f"{found.cost_ms:.0f} ms{' (predicted)' if found.predicted else ''}, "
                f"FLIP {found.flip:.4f}"
            )


def _result(run, document, size, views, path, search: Search) -> dict:
    candidates, shipped = search.candidates, search.shipped
    budget_ms, quality = search.budget_ms, search.quality
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
        "workers": search.where,
        "cost_model": None if search.model is None else search.model.to_dict(),
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
                # the search's time for it, predicted or measured, as the machine runs now
                "search_ms": c.cost_ms * shipped_ms / self.shipped.cost_ms,
                "predicted": c.predicted,
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
