"""After any sequence of edits the window draws what `sward render` draws of the saved document
(the far-field issue: after blade edits the designer once showed far grass that a fresh load
of the same document did not)."""

import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from core.image_diff import QUARTER, flip
from core.quality import technique_regions
from tests.widgets.conftest import grab

pytestmark = pytest.mark.gui
# the technique view's colours (thesis Figs. 7.1-7.6): geometry red, volume yellows (deeper or
# lighter with fewer slices), image-based blue; the window's process imports no GL module
TECHNIQUE_COLOURS = {
    "geometry": [(1.0, 0.15, 0.1)],
    "volume": [(1.0, 0.85, 0.1), (0.95, 0.62, 0.05), (1.0, 0.97, 0.38)],
    "image": [(0.15, 0.35, 1.0)],
}


def render(project, size, out, *extra) -> np.ndarray:
    """`sward render` of the project at the bookmarked view, as (h, w, 3) uint8."""
    r = subprocess.run(
        [sys.executable, "-m", "app.cli", "render", "--project", str(project),
         "--camera", "after edits", "--size", f"{size[0]}x{size[1]}", "--out", str(out), *extra],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    return np.asarray(Image.open(out).convert("RGB"))


def test_the_window_after_edits_draws_what_sward_render_draws_of_the_saved_project(
    window, qtbot, tmp_path
):
    panel = window.panel
    panel.param("preset").setValue("long thin meadow grass")
    qtbot.waitUntil(lambda: window.document.params(0).length_max == pytest.approx(0.65))
    for name, value in (("tilt_max", 12.0), ("length_min", 0.25), ("blade_count", 900)):
        panel.param(name).setValue(value)
        qtbot.waitUntil(lambda n=name, v=value: getattr(window.document.params(0), n) == v)
    panel.param("slices").setValue(4)
    window.light_panel.root.child("sun_elevation").setValue(30.0)
    window.viewport.set_camera(window.document.camera("grazing"))  # all three representations
    window.viewport.camera.orbit(25.0, 0.0)
    assert window.bookmark_view("after edits")
    shown = grab(window)
    path = tmp_path / "edited.sward"
    assert window.projects.save_as(path)

    h, w = shown.shape[:2]
    rendered = render(path, (w, h), tmp_path / "render.png")
    # the view shows every representation, each with the edits
    techniques = render(path, (w, h), tmp_path / "techniques.png", "--view", "techniques")
    shares = technique_regions(rendered, techniques, TECHNIQUE_COLOURS)
    assert all(shares[name].mean() > 0.02 for name in ("geometry", "volume", "image")), {
        name: float(mask.mean()) for name, mask in shares.items()
    }
    assert rendered.shape == shown.shape
    # the same code on the same document: alike but for the last bits of the rasteriser
    assert np.abs(rendered.astype(int) - shown.astype(int)).mean() < 1.0
    assert flip(rendered, shown, QUARTER)[0] < 0.01
