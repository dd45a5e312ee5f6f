"""Stored reference images: what the renderer drew at fixed cameras before an optimisation, kept
at quarter resolution (4 × 4 pixels averaged, core/image_diff.py), so that a speed-up that was
meant to keep the picture is checked against it (tests/render/test_reference_images.py) and
`sward bench --suite preview` reports how far the default frame moved.

Regenerate (only when a change of the picture is meant, and say so in the commit):

    .venv/bin/python -m benchmarks.references [NAME ...]
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

FOLDER = Path(__file__).with_name("references")
LIMIT = 0.02  # quarter-resolution FLIP a kept picture may move by (issue: faster frames)


@dataclass(frozen=True)
class Case:
    scene: str
    camera: str
    mode: str = "lod"  # a ViewMode: lod, geometry, volume, image
    size: tuple[int, int] = (480, 360)

    @property
    def name(self) -> str:
        w, h = self.size
        return f"{self.scene}-{self.camera}-{self.mode}-{w}x{h}"

    @property
    def path(self) -> Path:
        return FOLDER / f"{self.name}.png"


CASES = (
    Case("meadow", "default", size=(950, 720)),  # the designer's default frame (bench: preview)
    Case("meadow", "path"),
    Case("meadow", "hill"),
    Case("meadow", "default", "volume"),
    Case("bench", "zones"),
    Case("bench", "default", "volume"),
    Case("bench", "grazing", "image"),
    Case("landscape", "ridge", size=(320, 240)),
)


def by_name(name: str) -> Case:
    for case in CASES:
        if case.name == name:
            return case
    raise KeyError(name)


def render(case: Case, ctx=None) -> np.ndarray:
    """The case's frame at full size, (h, w, 3) uint8."""
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    doc = get_scene(case.scene).document()
    with HeadlessRenderer(doc, ctx, mode=case.mode) as renderer:
        image, _ = renderer.render(doc.camera(case.camera), case.size, measure=False)
    return image


def quarter(image: np.ndarray) -> np.ndarray:
    """The stored form: quarter resolution, uint8."""
    from core.image_diff import QUARTER, downsample

    return np.rint(downsample(image, QUARTER) * 255.0).astype(np.uint8)


def load(case: Case) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(case.path).convert("RGB"))


def moved(case: Case, image: np.ndarray) -> float:
    """FLIP of a full-size frame against the case's stored reference, at quarter resolution."""
    from core.image_diff import flip

    return flip(load(case), quarter(image))[0]


def write(cases) -> None:
    from PIL import Image

    FOLDER.mkdir(exist_ok=True)
    for case in cases:
        Image.fromarray(quarter(render(case))).save(case.path, optimize=True)
        print(f"wrote {case.path}")


if __name__ == "__main__":
    write([by_name(n) for n in sys.argv[1:]] if len(sys.argv) > 1 else CASES)
