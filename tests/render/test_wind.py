"""The wind moves the grass of every representation alike and nothing else (issue: wind)."""

import numpy as np
import pytest
from scipy.ndimage import binary_erosion

from app.scenes import get_scene
from core.quality import technique_regions
from core.wind import Wind
from render.grass_type import technique_colors

SIZE = (480, 270)


def _frames(headless, wind: Wind, times=(0.0, 0.5)):
    doc = get_scene("meadow").document()
    doc.wind = wind
    renderer = headless(doc)
    camera = doc.camera("default")
    renderer.pipeline.view = "techniques"
    techniques = renderer.render(camera, SIZE, measure=False)[0]
    renderer.pipeline.view = "shaded"
    frames = []
    for t in times:
        renderer.pipeline.time = t
        frames.append(renderer.render(camera, SIZE, measure=False)[0])
    return techniques, frames


def test_wind_moves_the_grass_of_every_representation_and_not_sky_or_path(headless):
    techniques, (before, after) = _frames(headless, Wind(enabled=True))
    regions = technique_regions(before, techniques, technique_colors())
    change = np.abs(before.astype(int) - after.astype(int)).max(axis=-1)
    for name, mask in regions.items():
        assert mask.sum() > 1000, f"the default camera sees little {name} grass"
        moved = float((change[mask] > 0).mean())
        # far away the blades move by less than a pixel: fewer pixels change there
        assert moved > (0.5 if name != "image" else 0.1), f"{name}: {moved:.3f} of it moved"
    grass = np.any(list(regions.values()), axis=0)
    # (bright blue: the grey rocks are bluish too, and blades lean over their edges)
    sky = ~grass & (before[..., 2] > before[..., 1]) & (before[..., 2] > 150)
    assert sky.sum() > 10_000 and not change[sky].any()
    # the bare path and the rocks, away from the blades that lean over their edges (their faint
    # tips, a pixel past what the technique view shows, sway too)
    bare = binary_erosion(~grass & ~sky, iterations=4)
    assert bare.sum() > 1000 and (change[bare] <= 8).all()


def test_still_air_draws_the_same_frame_at_any_time(headless):
    _, (before, after) = _frames(headless, Wind(enabled=False, gust_strength=0.9))
    assert np.array_equal(before, after)


@pytest.mark.parametrize("mode", ["geometry", "volume", "image"])
def test_each_representation_moves_on_its_own(headless, mode):
    """--only each representation: the wind moves it between two moments."""
    doc = get_scene("patch-grid").document()
    doc.wind = Wind(enabled=True, gust_strength=0.6)
    renderer = headless(doc, mode=mode)
    camera = doc.camera("grazing")
    frames = []
    for t in (0.0, 1.0):
        renderer.pipeline.time = t
        frames.append(renderer.render(camera, (320, 180), measure=False)[0].astype(int))
    grass = frames[0][..., 1] > frames[0][..., 2]
    assert (np.abs(frames[0] - frames[1]).max(axis=-1)[grass] > 0).mean() > 0.2


def test_every_representation_leans_with_the_one_field_at_the_same_moment(headless):
    """The wind view shows the lean each representation draws with: in the geometry, volume and
    image-based regions it is core/wind.py's field at the pixel's ground point at this moment —
    several times closer to it than to the field half a second later — so a gust seen in the
    blades continues through the volume and over the far field in step."""
    from core.picking import ground_hit, pixel_ray
    from core.wind import MAX_LEAN, lean

    doc = get_scene("meadow").document()
    doc.wind = Wind(True, 30.0, 12.0, 0.8, 20.0, 0.0, 1.5)  # gusts alone, fast and broad
    renderer = headless(doc)
    camera = doc.camera("default")
    moment = 1.3
    renderer.pipeline.time = moment
    shaded = renderer.render(camera, SIZE, measure=False)[0]
    renderer.pipeline.view = "techniques"
    techniques = renderer.render(camera, SIZE, measure=False)[0]
    renderer.pipeline.view = "wind"
    shown = renderer.render(camera, SIZE, measure=False)[0].astype(float)
    rng = np.random.default_rng(0)
    for name, mask in technique_regions(shaded, techniques, technique_colors()).items():
        whole = mask & (np.abs(shown[..., 2] - 64.0) <= 2.0)  # not blended with the soil
        rows, cols = np.nonzero(whole)
        assert rows.size > 500, name
        now, later = [], []
        for k in rng.choice(rows.size, size=150, replace=False):
            origin, direction = pixel_ray(camera, cols[k] + 0.5, rows[k] + 0.5, *SIZE)
            ground = ground_hit(doc.terrain, origin, direction)
            if ground is None:
                continue
            drawn = (shown[rows[k], cols[k], :2] / 255.0 - 0.5) * 2.0 * MAX_LEAN
            now.append(np.abs(drawn - lean(doc.wind, ground[[0, 2]], moment)).max())
            later.append(np.abs(drawn - lean(doc.wind, ground[[0, 2]], moment + 0.5)).max())
        assert len(now) > 100, name
        assert np.median(now) < 0.025, f"{name}: {np.median(now):.3f}"
        assert np.median(now) < 0.4 * np.median(later), f"{name} is out of step"


def test_while_the_wind_blows_the_blades_reach_farther(headless):
    """The wind's blade_reach moves the hand-over from the blades to the slices out while it
    blows (the slices hold the grass at rest), and only then."""
    doc = get_scene("meadow").document()
    renderer = headless(doc)
    camera = doc.camera("default")

    def blades(wind: Wind) -> int:
        doc.wind = wind
        renderer.pipeline.view = "shaded"
        shaded = renderer.render(camera, SIZE, measure=False)[0]
        renderer.pipeline.view = "techniques"
        techniques = renderer.render(camera, SIZE, measure=False)[0]
        regions = technique_regions(shaded, techniques, technique_colors())
        return int(regions["geometry"].sum())

    still = blades(Wind(enabled=False, blade_reach=1.5))
    assert still > 1000
    assert blades(Wind(enabled=True, blade_reach=1.0)) == pytest.approx(still, rel=0.05)
    assert blades(Wind(enabled=True, blade_reach=1.5)) > 1.2 * still


def test_a_gust_lights_the_far_grass_as_it_lights_the_blades(headless):
    """The patch-grid seen by the image-based grass alone and by the blades alone, a wide gust
    blowing one way and then the other: each way changes the light of both alike (core/facing.py
    bend_coefficients), the part that turns with the wind's way in the same direction and by a
    like amount."""
    changes = {}
    for mode in ("geometry", "image"):
        frames = []
        for direction in (None, 0.0, 180.0):
            doc = get_scene("patch-grid").document()
            doc.wind = Wind(
                enabled=direction is not None, direction=direction or 0.0, gust_strength=0.3,
                gust_scale=200.0, turbulence_strength=0.0,
            )  # fmt: skip
            frame = headless(doc, mode=mode).render(doc.camera("default"), SIZE, measure=False)[0]
            frames.append(frame.astype(float) / 255.0)
        still, along, against = frames
        grass = still[..., 1] > still[..., 2] + 0.05
        assert grass.mean() > 0.3
        changes[mode] = float(((along - still) - (against - still))[grass].mean()) / 2.0
    assert abs(changes["geometry"]) > 0.001, changes  # the blades' light turns with the wind
    assert 0.5 < changes["image"] / changes["geometry"] < 2.0, changes
