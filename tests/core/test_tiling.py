import numpy as np

from core.grid import INSTANCE_DTYPE, grid_instances
from core.tiling import mirror_bits


def test_mirror_bits_are_signs_decided_per_cell():
    cells = grid_instances(32, 32)["origin"]
    s = mirror_bits(cells, seed=3)
    assert s.shape == (1024, 2) and set(np.unique(s)) == {-1.0, 1.0}
    assert np.array_equal(s, mirror_bits(cells, seed=3))  # the same cells, the same mirrors
    assert not np.array_equal(s, mirror_bits(cells, seed=4))
    # all four mirrored versions of the patch appear, each about a quarter of the time
    combos = (s[:, 0] > 0) * 2 + (s[:, 1] > 0)
    shares = np.bincount(combos, minlength=4) / len(combos)
    assert np.all((shares > 0.18) & (shares < 0.32))


def test_mirror_bits_follow_the_cell_not_its_index():
    cells = grid_instances(8, 8)["origin"]
    s = mirror_bits(cells, seed=1)
    order = np.random.default_rng(0).permutation(len(cells))
    assert np.array_equal(mirror_bits(cells[order], seed=1), s[order])


def test_grid_instances_carry_size_mirror_and_config():
    plain = grid_instances(4, 2)
    assert plain.dtype == INSTANCE_DTYPE
    assert np.all(plain["size"] == 1) and np.all(plain["mirror"] == 1)
    tiled = grid_instances(4, 2, mirror_seed=5)
    assert np.any(tiled["mirror"] < 0)
    # the config transform maps every cell's own square into the design maps, covering 0 … 1
    lo = plain["config"][:, :2]
    hi = lo + plain["config"][:, 2:]
    assert np.allclose(lo.min(axis=0), 0) and np.allclose(hi.max(axis=0), 1)
    assert np.allclose(plain["config"][:, 2:], (1 / 4, 1 / 2))
