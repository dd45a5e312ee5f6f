import numpy as np
import pytest

from core.brush import ALL_TYPES, Brush, Stroke, falloff
from core.design_maps import DesignMaps


@pytest.mark.parametrize("kind", ["smooth", "linear", "constant", "sharp"])
def test_falloffs_run_from_one_at_the_centre_to_zero_at_the_rim(kind):
    r = np.linspace(0.0, 1.2, 61)
    w = falloff(kind, r)
    assert w[0] == 1.0 and np.all(w[r >= 1.0] == 0.0)
    assert np.all(np.diff(w) <= 1e-7)  # never rises outwards


def test_a_dab_changes_only_the_footprint_and_announces_only_it():
    maps = DesignMaps(128)
    seen = []
    maps.changed.connect(lambda name, rect: seen.append((name, rect)))
    stroke = Stroke(maps, "density", Brush(size=16, strength=1.0, value=(0.0,), falloff="constant"))
    stroke.add(40.0, 50.0)
    d = maps.layer("density")[..., 0]
    yy, xx = np.mgrid[0:128, 0:128] + 0.5
    inside = np.hypot(xx - 40, yy - 50) < 7.5
    outside = np.hypot(xx - 40, yy - 50) > 8.5
    assert np.all(d[inside] == 0.0) and np.all(d[outside] == 1.0)
    assert np.all(maps.layer("density")[..., 1:] == 1.0)  # the other grass types untouched
    ((name, (x, y, w, h)),) = seen
    assert name == "density" and w <= 18 and h <= 18
    assert x <= 32 and x + w >= 48 and y <= 42 and y + h >= 58


def test_dabs_follow_the_path_at_the_spacing_and_undo_restores_exactly():
    maps = DesignMaps.procedural(256, seed=3)
    before = maps.stack.copy()
    brush = Brush(size=20, strength=0.8, value=(0.9, 0.2, 0.1, 1.0), spacing=0.25)
    stroke = Stroke(maps, "color", brush)
    stroke.add(10.0, 128.0)
    stroke.add(210.0, 128.0)  # 200 texels at a 5-texel spacing
    assert stroke.dabs == 41
    changed = np.any(maps.stack != before, axis=-1)
    rows, cols = np.nonzero(changed[1])
    assert rows.min() >= 117 and rows.max() <= 139 and cols.min() >= 0 and cols.max() <= 221
    stroke.finish()
    painted = maps.stack.copy()
    stroke.undo()
    assert np.array_equal(maps.stack, before)
    # only the touched tiles (2 rows x 4 columns of 64²) were kept, before and after
    assert len(stroke.saved) == 8 and stroke.memory_bytes == 2 * 8 * 64 * 64 * 4 * 4
    stroke.redo()
    assert np.array_equal(maps.stack, painted)
    x, y, w, h = stroke.bounds
    assert x == 0 and y <= 117 and y + h >= 140 and x + w >= 222


def test_erase_removes_grass_and_smooth_evens_out():
    maps = DesignMaps(64)
    rng = np.random.default_rng(1)
    maps.write("density", 0, 0, rng.random((64, 64)))
    noisy = maps.layer("density")[..., 0].copy()
    smooth = Stroke(maps, "density", Brush(size=30, strength=1.0, mode="smooth"))
    smooth.add(32.0, 32.0)
    centre = (slice(24, 40), slice(24, 40))
    assert maps.layer("density")[..., 0][centre].std() < 0.6 * noisy[centre].std()
    erase = Stroke(maps, "density", Brush(size=12, strength=1.0, falloff="constant", mode="erase"))
    erase.add(32.0, 32.0)
    assert np.all(maps.layer("density")[28:36, 28:36, 0] == 0.0)  # bare where it erased
    maps.fill("ambient", 0.3)  # a painted shadow ...
    shade = Stroke(maps, "ambient", Brush(size=12, strength=1.0, falloff="constant", mode="erase"))
    shade.add(32.0, 32.0)
    assert np.all(maps.layer("ambient")[28:36, 28:36] == 1.0)  # ... erased to neutral light


def test_fill_sets_the_whole_map_in_one_step_and_bad_brushes_are_refused():
    maps = DesignMaps(32)
    fill = Stroke(maps, "ambient", Brush(value=(0.5, 0.5, 0.5), mode="fill"))
    assert np.all(maps.layer("ambient") == 0.5)
    fill.undo()
    assert np.all(maps.layer("ambient") == 1.0)
    with pytest.raises(ValueError, match="needs 3 value"):
        Stroke(maps, "ambient", Brush(value=(0.5,)))
    with pytest.raises(ValueError, match="brush size 0"):
        Brush(size=0)
    with pytest.raises(ValueError, match="unknown falloff 'soft'"):
        Brush(falloff="soft")


def test_one_value_clears_every_grass_type_at_once():
    maps = DesignMaps(64)
    stroke = Stroke(
        maps, "density", Brush(size=10, strength=1.0, value=(0.0,), falloff="constant"), ALL_TYPES
    )
    stroke.add(32.0, 32.0)
    assert np.all(maps.layer("density")[30:34, 30:34] == 0.0)  # all four channels
    assert np.all(maps.layer("density")[:20] == 1.0)
