import numpy as np
import pytest

from core.design_maps import LAYERS, DesignMaps


def test_new_maps_are_neutral():
    maps = DesignMaps(16, 8)
    assert maps.size == (16, 8)
    assert np.all(maps.layer("density") == 1)
    assert np.all(maps.layer("color")[..., 3] == 0)  # no colour modulation
    assert np.all(maps.layer("ambient") == 1) and np.all(maps.layer("diffuse") == 1)
    assert np.all(maps.layer("height") == 0)
    assert np.all(maps.layer("trample") == 0.5)  # the grass stands upright
    names = ["density", "color", "ambient", "diffuse", "height", "trample"]
    assert [layer.name for layer in LAYERS] == names


def test_write_announces_only_the_rectangle_it_changed():
    maps = DesignMaps(32)
    seen = []
    maps.changed.connect(lambda name, rect: seen.append((name, rect)))
    rect = maps.write("density", 28, -2, np.zeros((6, 8)))  # hangs over two edges
    assert rect == (28, 0, 4, 4) and seen == [("density", (28, 0, 4, 4))]
    d = maps.layer("density")[..., 0]
    assert np.all(d[0:4, 28:32] == 0) and d.sum() == 32 * 32 - 16
    maps.write("color", 0, 0, np.ones((2, 2, 4)))
    assert seen[-1] == ("color", (0, 0, 2, 2))
    assert maps.layer("density").flags.writeable is False


@pytest.mark.parametrize(
    ("name", "values", "message"),
    [
        ("density", np.zeros((2, 2, 3)), "density map values must be"),
        ("color", np.zeros((2, 2)), "color map values must be"),
        ("density", np.full((2, 2), np.nan), "finite"),
        ("grass", np.zeros((2, 2)), "unknown design map 'grass'"),
    ],
)
def test_bad_edits_are_refused_with_the_map_named(name, values, message):
    maps = DesignMaps(8)
    before = maps.stack.copy()
    with pytest.raises((ValueError, KeyError), match=message):
        maps.write(name, 0, 0, values)
    assert np.array_equal(maps.stack, before)  # nothing painted is lost


def test_impossible_size_is_refused():
    with pytest.raises(ValueError, match="design map width = 0"):
        DesignMaps(0)


def test_procedural_maps_tint_lightly_and_keep_full_density():
    maps = DesignMaps.procedural(64, seed=2)
    color = maps.layer("color")
    assert np.all(maps.layer("density") == 1)
    assert 0 < color[..., 3].max() <= 0.25 and color[..., 3].std() > 0.01
    assert not np.array_equal(color, DesignMaps.procedural(64, seed=3).layer("color"))
