"""All-geometry reference frames kept on disk (`sward tune`, `sward quality`): a reference
takes seconds to minutes on a CPU renderer and depends only on what the grass looks like —
the document without its LOD settings, the camera, the size and the wind's moment — so a
second run finds it. Kept beside the derived sums (render/derived_cache.py), in references/,
as PNG, the newest up to MAX_BYTES; the file name carries a digest of the code that draws
(core/, render/, shaders/), so a reference drawn by other code is never read."""

from __future__ import annotations

import hashlib
import json
import math
import os
from functools import lru_cache
from pathlib import Path

import numpy as np

import core
import render
import shaders
from core.camera import Camera
from core.document import Document
from render import derived_cache

MAX_BYTES = 128 * 2**20
TIME_KEY = "sward:geometry_ms"  # the PNG text that holds how long the frame took to draw
_SKIP = ("lod", "name", "description", "cameras", "default_camera", "paths")


@lru_cache(maxsize=1)
def _code() -> str:
    digest = hashlib.blake2b(digest_size=8)
    for package in (core, render, shaders):
        base = Path(package.__file__).parent
        for source in sorted([*base.glob("*.py"), *base.glob("*.glsl")]):
            digest.update(source.name.encode())
            digest.update(source.read_bytes())
    return digest.hexdigest()


def key(document: Document, camera: Camera, size: tuple[int, int], time: float) -> str:
    """A digest of everything the reference frame depends on."""
    from core.project_file import document_data

    data = document_data(document)
    for name in _SKIP:
        data.pop(name, None)
    for kind in data.get("grass", []):
        kind.pop("lod", None)
    digest = hashlib.blake2b(digest_size=16)
    digest.update(json.dumps(data, sort_keys=True, default=str).encode())
    digest.update(np.ascontiguousarray(document.maps.stack).tobytes())
    view = (tuple(camera.eye), tuple(camera.target), camera.fov_y, camera.near, camera.far)
    moment = float(time) if document.wind.enabled else 0.0  # still grass: any moment is one
    digest.update(repr((view, tuple(size), moment)).encode())
    return digest.hexdigest()


def _path(name: str) -> Path | None:
    base = derived_cache.folder()
    if base is None:
        return None
    folder = base / "references"
    try:
        folder.mkdir(exist_ok=True)
    except OSError:
        return None
    return folder / f"geometry-{_code()}-{name}.png"


def load(name: str, size: tuple[int, int]) -> np.ndarray | None:
    """The reference kept under `name` as (h, w, 3) uint8, or None."""
    kept = load_timed(name, size)
    return None if kept is None else kept[0]


def load_timed(name: str, size: tuple[int, int]) -> tuple[np.ndarray, float | None] | None:
    """The reference kept under `name` and how long it took to draw (ms) where that was
    measured, or None."""
    from PIL import Image

    path = _path(name)
    if path is None or not path.is_file():
        return None
    try:
        with Image.open(path, formats=["PNG"]) as image:
            if image.size != tuple(size) or image.mode != "RGB":
                return None
            text = getattr(image, "text", {}).get(TIME_KEY)
            ms = float(text) if text is not None else None
            return np.asarray(image).copy(), ms if ms is None or math.isfinite(ms) else None
    except (OSError, ValueError):  # not whole, not an image, a time that is no number
        return None


def save(name: str, image: np.ndarray, ms: float | None = None) -> None:
    """Keep `image` under `name`, with the time it took to draw when `ms` gives it."""
    from PIL import Image, PngImagePlugin

    path = _path(name)
    if path is None:
        return
    partial = path.with_name(f".{path.name}.{os.getpid()}")
    info = PngImagePlugin.PngInfo()
    if ms is not None:
        info.add_text(TIME_KEY, f"{ms:.3f}")
    try:
        Image.fromarray(image).save(partial, format="PNG", pnginfo=info)
        os.replace(partial, path)
        _prune(path.parent)
    except OSError:
        partial.unlink(missing_ok=True)


def _prune(folder: Path) -> None:
    derived_cache.keep_newest(list(folder.glob("geometry-*.png")), MAX_BYTES)


def geometry_frame(renderer, camera: Camera, size: tuple[int, int]) -> tuple[np.ndarray, bool]:
    """The all-geometry frame of `renderer`'s document (a HeadlessRenderer) at this camera and
    the pipeline's wind moment: the kept one, or drawn and kept; and whether it was drawn."""
    name = key(renderer.binding.document, camera, size, renderer.pipeline.time)
    image = load(name, size)
    if image is not None:
        return image, False
    image, ms = _drawn(renderer, camera, size)
    save(name, image, ms)
    return image, True


def draw(renderer, camera: Camera, size: tuple[int, int]) -> np.ndarray:
    """The all-geometry frame drawn now, not kept (a worker of `sward tune` draws it; the
    search keeps it where it runs)."""
    return _drawn(renderer, camera, size)[0]


def _drawn(renderer, camera: Camera, size: tuple[int, int]) -> tuple[np.ndarray, float]:
    from core.view_mode import ViewMode
    from render.comparison import drawn_as

    with drawn_as(renderer.pipeline, ViewMode.GEOMETRY):
        image, stats = renderer.render(camera, size, measure=True)
    return image, stats.t_a_ms
