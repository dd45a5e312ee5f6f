import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from core.grid import grid_instances
from core.lod import LodConfig, opacity, select, weight_near


@given(
    w=st.floats(0.0, 1.0),
    ld=st.floats(0.05, 1.0),
    eps=st.floats(0.0, 0.2),
)
def test_each_blade_is_shared_out_exactly_once(w, ld, eps):
    t = np.linspace(1e-4, 1.0, 400)
    near = opacity(t, w, ld, eps, far=False)
    far = opacity(t, w, ld, eps, far=True)
    visible = t <= ld
    assert np.allclose((near + far)[visible], 1.0)
    assert np.all((near + far)[~visible] == 0.0)
    assert np.all((near >= 0) & (near <= 1) & (far >= 0) & (far <= 1))


def test_blades_move_over_gradually_with_distance():
    t = np.random.default_rng(0).random(5000)
    d = np.linspace(2.0, 4.0, 41)
    w = weight_near(d, 2.5, 3.5)
    assert w[0] == 1.0 and w[-1] == 0.0 and np.all(np.diff(w) <= 0)
    near_share = [opacity(t, wi, 1.0, 0.05, far=False).mean() for wi in w]
    assert np.all(np.diff(near_share) <= 1e-9)  # monotone hand-over, no jumps
    assert np.max(np.abs(np.diff(near_share))) < 0.06


def test_smoothstep_window_only_touches_blades_near_w():
    t = np.array([0.3, 0.49, 0.5, 0.51, 0.7])
    near = opacity(t, 0.5, 1.0, 0.05, far=False)
    assert near[0] == 1.0 and near[-1] == 0.0 and 0.0 < near[2] < 1.0


def test_select_puts_every_cell_in_a_zone_and_band_cells_in_two():
    cells = grid_instances(16, 16)
    config = LodConfig(geometry_end=3.0, volume_end=6.0, transition=1.0)
    parts = select(cells, np.array([0.0, 1.0, 0.0]), config)
    total = sum(p.size for p in parts.values())
    in_two = total - cells.size
    assert in_two > 0  # transition bands exist
    both = parts["geometry"][parts["geometry"]["lod"][:, 0] < 2.0]
    assert both.size and np.all(both["lod"][:, 1] == 0.0)
    far_side = parts["volume"][parts["volume"]["lod"][:, 1] == 1.0]
    assert far_side.size == both.size  # the same band cells, on the far side
    assert parts["image"].size > 0


def test_bad_zones_are_refused():
    with pytest.raises(ValueError, match="increasing"):
        LodConfig(geometry_end=5.0, volume_end=2.0)
