"""Shared fixtures: one standalone EGL context for the session, GL error checks per test, and
`headless`, which makes a fresh renderer for a document on that context (released after the
test). Nothing here imports GL or Qt at import time: tests/core runs without either.

Tests marked `gui` (real windows under Xvfb) run in a process of their own, as `make test` runs
`pytest -m "not gui"` and then `pytest -m gui`: the window's frames come from render processes
(render/render_server.py), and keeping the EGL tests apart keeps each run's GL state its own.
"""

from __future__ import annotations

import os

import numpy as np
import pytest


@pytest.fixture(scope="session", autouse=True)
def kept_sums(tmp_path_factory):
    """The folder where the run keeps the light sums it derives (render/derived_cache.py): one
    for the run, empty at its start, shared by xdist's workers (the cache's claim files let two
    processes build and read it at once), by `sward` run as a process (tests/test_cli.py
    `sward`) and by the windows' render processes, as a user's runs and windows share theirs.
    A sum read from it is the one a build gives (its name carries the content's digest and
    core's code); the tests of the cache and of when sums are built name folders of their
    own or turn it off."""
    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent  # each worker's base folder lies in the run's
    folder = root / "sums"
    folder.mkdir(exist_ok=True)
    os.environ["SWARD_CACHE"] = str(folder)
    return folder


@pytest.fixture(scope="session")
def gl_ctx():
    from render import context

    ctx = context.standalone()
    yield ctx
    ctx.release()


@pytest.fixture
def ctx(gl_ctx):
    assert gl_ctx.error == "GL_NO_ERROR"
    yield gl_ctx
    assert gl_ctx.error == "GL_NO_ERROR"
    gl_ctx.disable_direct(0x809E)
    gl_ctx.disable(gl_ctx.DEPTH_TEST | gl_ctx.CULL_FACE | gl_ctx.BLEND)


@pytest.fixture
def headless(ctx):
    """headless(document, mode=..., view=...) -> a HeadlessRenderer on the shared context."""
    from render.headless import HeadlessRenderer

    made = []

    def make(document, **kwargs):
        renderer = HeadlessRenderer(document, ctx, **kwargs)
        made.append(renderer)
        return renderer

    yield make
    for renderer in made:
        renderer.release()


def grass_mask(image: np.ndarray) -> np.ndarray:
    """Pixels that show grass: clearly green, unlike sky, soil or fog."""
    rgb = image.astype(np.float32)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    return (g > 1.12 * r + 2) & (g > 1.25 * b + 2)


def coverage(image: np.ndarray) -> float:
    return float(grass_mask(image).mean())


def pixel_rays(camera, size: tuple[int, int]) -> np.ndarray:
    """Direction (unnormalised) from the eye through every pixel's centre, rows top first like
    a rendered image: (h, w, 3)."""
    w, h = size
    inv = np.linalg.inv(camera.projection(w / h) @ camera.view())
    xs = (np.arange(w) + 0.5) / w * 2 - 1
    ys = 1 - (np.arange(h) + 0.5) / h * 2
    gx, gy = np.meshgrid(xs, ys)
    far = np.stack([gx, gy, np.ones_like(gx), np.ones_like(gx)], -1) @ inv.T
    return far[..., :3] / far[..., 3:] - camera.eye


def covered(image: np.ndarray, bare: np.ndarray, tolerance: int = 10) -> float:
    """Fraction of pixels that differ from `bare` (the same view without grass)."""
    diff = np.abs(image.astype(np.int16) - bare.astype(np.int16)).max(axis=-1)
    return float((diff > tolerance).mean())


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config, items):
    kinds = {"gui" in item.keywords for item in items}
    if kinds == {True, False}:
        raise pytest.UsageError(
            "window tests (marker gui) and EGL tests run in processes of their own; run "
            '`pytest -m "not gui"` and `pytest -m gui` separately (as `make test` does)'
        )
