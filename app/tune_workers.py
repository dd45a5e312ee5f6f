"""`sward tune --workers N | --ray ADDRESS`: a sweep's renders in other processes. Each worker
holds the document, its own GL context and renderer (app/tune.py's TuneRun) and, once they are
drawn, the references; the search hands it views to draw references of and candidates to
evaluate, and gathers the results as a local run would (references into this machine's kept
frames, candidates into the front).

Local workers are processes of this machine (one executor of one process each, so that every
worker can be told the references); Ray workers are actors of an existing cluster (the
optional extra `sward[cluster]`), each a process with its own context on some node. Both answer
with concurrent.futures.Future, so the search does not care which."""

from __future__ import annotations

import multiprocessing
import signal
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from typing import Any

import numpy as np

from core.camera import Camera
from core.tuning import Candidate, Knobs


class TuneWorker:
    """One worker: the document rebuilt from its data, a renderer on a context of its own."""

    def __init__(
        self,
        data: dict,
        stack: np.ndarray,
        size: tuple[int, int],
        views: list[tuple[str, list[Camera]]],
    ) -> None:
        from app.tune_run import TuneRun
        from core.project_file import document_from_data

        document = document_from_data(data, stack)
        self.run = TuneRun(document, size, views, say=lambda _text: None)

    def ready(self) -> bool:
        return True

    def view(self, camera: Camera, reference: bool) -> tuple[np.ndarray | None, dict]:
        return self.run.view(camera, reference)

    def set_references(self, references: list, masks: list) -> None:
        self.run.references, self.run.masks = references, masks

    def evaluate(self, knobs: Knobs) -> Candidate | None:
        return self.run.evaluate(knobs)


class Pool:
    """Workers that each answer a call (the name of a TuneWorker method and its arguments)
    with a Future. Callers name the method by itself (`TuneWorker.evaluate`)."""

    def __init__(self, calls: list[Callable[..., Future]], close: Callable[[], None], where: str):
        self.calls, self._close, self.where = calls, close, where

    def __len__(self) -> int:
        return len(self.calls)

    def everyone(self, method: Callable, *args) -> list:
        """Every worker calls `method`; their answers."""
        return [f.result() for f in [call(method.__name__, *args) for call in self.calls]]

    def map(self, method: Callable, items: list[tuple]) -> Iterator[tuple[int, Any]]:
        """`method(*item)` for each item, every worker kept busy: (index, answer) as they
        come."""
        waiting = list(enumerate(items))
        running: dict[Future, tuple[int, int]] = {}
        idle = list(range(len(self.calls)))
        try:
            while waiting or running:
                while waiting and idle:
                    worker = idle.pop()
                    index, item = waiting.pop(0)
                    running[self.calls[worker](method.__name__, *item)] = (worker, index)
                done, _ = wait(running, return_when=FIRST_COMPLETED)
                for future in done:
                    worker, index = running.pop(future)
                    idle.append(worker)
                    yield index, future.result()
        finally:
            for future in running:
                future.cancel()

    def close(self) -> None:
        self._close()


# -- local processes ------------------------------------------------------------------------------
_worker: TuneWorker | None = None


def _start(data, stack, size, views) -> None:
    global _worker
    # Ctrl+C belongs to the search, which keeps what it found and then closes the workers
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _worker = TuneWorker(data, stack, size, views)


def _call(method: str, *args):
    assert _worker is not None
    return getattr(_worker, method)(*args)


def local_pool(count: int, setup: tuple) -> Pool:
    """`count` processes of this machine, started afresh (spawn: a GL context does not survive
    a fork)."""
    spawn = multiprocessing.get_context("spawn")
    executors = [
        ProcessPoolExecutor(1, mp_context=spawn, initializer=_start, initargs=setup)
        for _ in range(count)
    ]

    def call_of(executor: ProcessPoolExecutor) -> Callable[..., Future]:
        return lambda method, *args: executor.submit(_call, method, *args)

    def close() -> None:
        for executor in executors:
            executor.shutdown(wait=True, cancel_futures=True)

    pool = Pool([call_of(e) for e in executors], close, f"{count} local processes")
    pool.everyone(TuneWorker.ready)  # a worker that cannot start says so here
    return pool


# -- a Ray cluster --------------------------------------------------------------------------------
class ClusterError(Exception):
    """The cluster cannot be used: not installed, not reached, no CPU to place a worker on."""


def _reachable(address: str, timeout_s: float = 5.0) -> None:
    """Ray waits for a cluster that does not answer; a host:port that takes no connection is
    refused here, in seconds. Other forms ("auto", "ray://…") go to Ray as they are."""
    import socket

    host, sep, port = address.rpartition(":")
    if not sep or "/" in address or not port.isdigit():
        return
    try:
        socket.create_connection((host, int(port)), timeout=timeout_s).close()
    except OSError as exc:
        raise ClusterError(f"--ray {address}: no Ray cluster answers there ({exc})") from None


def ray_pool(address: str, setup: tuple, most: int | None = None) -> Pool:
    """One worker per CPU of the cluster at `address` (at most `most`). The code of this run
    travels with the job, so every node draws with the same code as the references kept here;
    the nodes need Sward's dependencies (`pip install sward[cluster]`)."""
    try:
        import ray
    except ImportError:
        raise ClusterError(
            "--ray needs Ray: pip install 'sward[cluster]' (or pip install ray)"
        ) from None
    import app
    import core
    import render
    import shaders

    _reachable(address)
    try:
        ray.init(
            address=address,
            runtime_env={"py_modules": [app, core, render, shaders]},
            log_to_driver=False,
            logging_level="ERROR",
        )
    except (ConnectionError, ValueError, RuntimeError) as exc:
        raise ClusterError(f"--ray {address}: no Ray cluster there ({exc})") from None
    cpus = int(ray.cluster_resources().get("CPU", 0))
    if cpus < 1:
        ray.shutdown()
        raise ClusterError(f"--ray {address}: the cluster has no CPU to run a worker on")
    count = min(cpus, most) if most else cpus
    remote = ray.remote(num_cpus=1)(TuneWorker)
    # one copy of the document in the object store, not one per worker (a reference passed as
    # an argument arrives as its value)
    refs = [ray.put(part) for part in setup]
    actors = [remote.remote(*refs) for _ in range(count)]

    def call_of(actor) -> Callable[..., Future]:
        return lambda method, *args: getattr(actor, method).remote(*args).future()

    def close() -> None:
        for actor in actors:
            ray.kill(actor)
        ray.shutdown()

    pool = Pool([call_of(a) for a in actors], close, f"{count} Ray workers at {address}")
    try:
        pool.everyone(TuneWorker.ready)
    except Exception as exc:  # an actor that died while starting: its node cannot draw
        close()
        raise ClusterError(f"--ray {address}: a worker could not start: {exc}") from None
    return pool
