import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from core.heights import bilinear, cell_ranges, hills


def test_bilinear_hits_texel_centres_and_interpolates_between():
    h = np.array([[0.0, 1.0], [2.0, 3.0]], np.float32)  # rows along v
    assert bilinear(h, np.array([0.25]), np.array([0.25]))[0] == 0.0
    assert bilinear(h, np.array([0.75]), np.array([0.75]))[0] == 3.0
    assert bilinear(h, np.array([0.5]), np.array([0.25]))[0] == 0.5
    assert bilinear(h, np.array([0.0]), np.array([1.0]))[0] == 2.0  # clamped at the edge


@settings(max_examples=25, deadline=None)
@given(
    map_size=st.integers(2, 40),
    columns=st.integers(1, 30),
    rows=st.integers(1, 30),
    seed=st.integers(0, 100),
)
def test_cell_ranges_enclose_the_surface(map_size, columns, rows, seed):
    heights = np.random.default_rng(seed).random((map_size, map_size)).astype(np.float32)
    lo, hi = cell_ranges(heights, 5.0, columns, rows)
    # dense random points of every cell lie within its range
    rng = np.random.default_rng(seed + 1)
    ix = rng.integers(0, columns, 4000)
    iz = rng.integers(0, rows, 4000)
    u = (ix + rng.random(4000)) / columns
    v = (iz + rng.random(4000)) / rows
    y = bilinear(heights, u, v) * 5.0
    assert np.all(y >= lo[ix, iz]) and np.all(y <= hi[ix, iz])


def test_hills_span_zero_to_one_and_vary_smoothly():
    h = hills(64, seed=3)
    assert h.min() == 0.0 and h.max() == 1.0
    assert np.abs(np.diff(h, axis=0)).max() < 0.2
