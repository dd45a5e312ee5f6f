"""Trampled grass: every representation lays its grass over as the trample map says, as core
computes it (the wind's test pattern, tests/render/test_wind.py)."""

import numpy as np
import pytest

from app.scenes import get_scene
from core.quality import technique_regions
from core.trample import encode, lean_at
from render.grass_type import technique_colors

SIZE = (480, 270)


def _trodden(doc, amount=None):
    """The trample map of `doc` painted with leans that turn once across the terrain and
    swell and fade along it (every texel, so the lean is known at any ground point)."""
    w, h = doc.maps.size
    v, u = np.mgrid[0:h, 0:w]
    turn = 2.0 * np.pi * (u + 0.5) / w
    size = 0.45 + 0.25 * np.sin(2.0 * np.pi * (v + 0.5) / (h / 2)) if amount is None else amount
    lean = np.stack([np.cos(turn), np.sin(turn)], axis=-1) * np.asarray(size)[..., None]
    doc.maps.write("trample", 0, 0, encode(lean))


def test_every_representation_leans_with_the_trample_map(headless):
    """The wind view shows the lean each representation draws with: in the geometry, volume and
    image-based regions, wind off, it is core/trample.py's lean at the pixel's ground point —
    far nearer it than upright grass is."""
    from core.picking import ground_hit, pixel_ray
    from core.wind import MAX_LEAN

    doc = get_scene("meadow").document()
    _trodden(doc)
    renderer = headless(doc)
    camera = doc.camera("default")
    shaded = renderer.render(camera, SIZE, measure=False)[0]
    renderer.pipeline.view = "techniques"
    techniques = renderer.render(camera, SIZE, measure=False)[0]
    renderer.pipeline.view = "wind"
    shown = renderer.render(camera, SIZE, measure=False)[0].astype(float)
    texels = doc.maps.layer("trample")
    terrain = doc.terrain
    rng = np.random.default_rng(0)
    for name, mask in technique_regions(shaded, techniques, technique_colors()).items():
        whole = mask & (np.abs(shown[..., 2] - 64.0) <= 2.0)  # not blended with the soil
        rows, cols = np.nonzero(whole)
        assert rows.size > 500, name
        errors, sizes = [], []
        for k in rng.choice(rows.size, size=150, replace=False):
            origin, direction = pixel_ray(camera, cols[k] + 0.5, rows[k] + 0.5, *SIZE)
            ground = ground_hit(terrain, origin, direction)
            if ground is None:
                continue
            u = (ground[0] - terrain.origin[0]) / terrain.columns
            v = (ground[2] - terrain.origin[1]) / terrain.rows
            want = lean_at(texels, np.array([u]), np.array([v]))[0]
            drawn = (shown[rows[k], cols[k], :2] / 255.0 - 0.5) * 2.0 * MAX_LEAN
            errors.append(np.abs(drawn - want).max())
            sizes.append(np.abs(want).max())
        assert len(errors) > 100, name
        assert np.median(errors) < 0.04, f"{name}: {np.median(errors):.3f}"
        assert np.median(errors) < 0.15 * np.median(sizes), f"{name} stands upright"


@pytest.mark.parametrize("mode", ["geometry", "volume", "image"])
def test_each_representation_lays_its_grass_over(headless, mode):
    """--only each representation: the patch grid trampled one way looks otherwise than upright
    and than trampled the other way."""
    doc = get_scene("patch-grid").document()
    renderer = headless(doc, mode=mode)
    camera = doc.camera("grazing")
    frames = [renderer.render(camera, (320, 180), measure=False)[0].astype(int)]
    for amount in (0.6, -0.6):
        w, h = doc.maps.size
        doc.maps.write("trample", 0, 0, encode(np.tile([amount, 0.0], (h, w, 1))))
        frames.append(renderer.render(camera, (320, 180), measure=False)[0].astype(int))
    grass = frames[0][..., 1] > frames[0][..., 2]
    for a, b in ((0, 1), (0, 2), (1, 2)):
        changed = (np.abs(frames[a] - frames[b]).max(axis=-1)[grass] > 8).mean()
        assert changed > 0.1, f"{mode}: frames {a} and {b} differ in {changed:.3f} of the grass"
