import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from core.params import PRESETS, PatchParams
from core.patch import blade_texture, generate_patch
from core.segments import level_count, level_indices, level_rows

SMALL = PatchParams(blade_count=300)


@settings(max_examples=20, deadline=None)
@given(
    blades=st.integers(1, 400),
    subdivisions=st.integers(1, 8),
    tilt=st.floats(0.0, 85.0),
    bending=st.floats(0.0, 0.95),
    seed=st.integers(0, 2**31 - 1),
)
def test_geometry_invariants(blades, subdivisions, tilt, bending, seed):
    params = PatchParams(
        blade_count=blades,
        subdivisions=subdivisions,
        tilt_min=0.0,
        tilt_max=tilt,
        bending=bending,
        seed=seed,
    )
    patch = generate_patch(params)
    v = patch.vertices
    assert v.size == blades * (subdivisions + 1) * 2
    assert patch.indices.size == blades * subdivisions * 6
    assert patch.indices.max() == v.size - 1
    # roots inside the unit square, and every vertex carries its blade's root
    assert np.all((patch.roots >= 0) & (patch.roots < 1))
    per_blade = v.reshape(blades, -1)
    assert np.array_equal(per_blade["root"][:, 0], patch.roots)
    # normals unit length
    n = v["normal"]
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-5)
    assert np.all(v["position"][:, 1] >= -1e-6)
    assert np.all(v["position"][:, 1] <= params.patch_height + 1e-5)


def test_normals_orthogonal_to_trajectory_derivative():
    params = PatchParams(blade_count=200, subdivisions=6, tilt_min=10, tilt_max=60, bending=0.3)
    patch = generate_patch(params)
    s = params.subdivisions
    pos = patch.vertices["position"].reshape(200, s + 1, 2, 3).mean(axis=2)  # strip centre line
    normal = patch.vertices["normal"].reshape(200, s + 1, 2, 3)[:, :, 0]
    # p(t) = b t + g t² sampled at equal t: the derivative at interior samples is the central
    # difference (exact for a quadratic)
    deriv = (pos[:, 2:] - pos[:, :-2]) / 2.0
    deriv /= np.linalg.norm(deriv, axis=-1, keepdims=True)
    dots = np.abs(np.sum(deriv * normal[:, 1:-1], axis=-1))
    assert dots.max() < 1e-3


def test_same_seed_same_patch_other_seed_other_patch():
    a = generate_patch(SMALL)
    b = generate_patch(SMALL)
    c = generate_patch(SMALL.replace(seed=SMALL.seed + 1))
    assert a.vertices.tobytes() == b.vertices.tobytes()
    assert a.vertices.tobytes() != c.vertices.tobytes()


def test_lengths_follow_the_parameters():
    short = generate_patch(PRESETS["short-cut turf"])
    tall = generate_patch(PRESETS["long thin meadow grass"])
    assert short.height < 0.1 < tall.height


def test_colour_variation_varies_blades():
    flat = generate_patch(SMALL.replace(blade_color_variation=0.0, vertex_light_variation=0.0))
    varied = generate_patch(SMALL.replace(blade_color_variation=0.8))
    tip = lambda p: p.vertices["color"].reshape(300, -1, 3)[:, -1]  # noqa: E731
    assert tip(flat).std(axis=0).max() < 1e-4
    assert tip(varied).std(axis=0).max() > 0.02


def test_blade_texture_has_a_pointed_tip():
    tex = blade_texture()
    alpha = tex[..., 3].astype(float) / 255
    assert alpha[10].mean() > 0.8  # near the root: full width
    assert alpha[-3].mean() < 0.3  # near the tip: narrow


@pytest.mark.parametrize("subdivisions", [1, 2, 3, 4, 5, 8])
def test_each_segment_level_keeps_whole_rows_root_and_tip_and_the_next_levels(subdivisions):
    """Blades far away are drawn through fewer rows of their strip (core/segments.py): the same
    vertices, the root and the tip kept, the strip still closed, each level about half the
    segments of the one before and holding the rows of the one after, the last one segment."""
    params = PatchParams(blade_count=7, subdivisions=subdivisions)
    patch = generate_patch(params)
    per_blade = (subdivisions + 1) * 2
    count = level_count(subdivisions)
    assert np.array_equal(level_indices(7, subdivisions, 0), patch.indices)
    assert list(level_rows(subdivisions, count - 1)) == [0, subdivisions]
    for level in range(count):
        rows = level_rows(subdivisions, level)
        assert rows[0] == 0 and rows[-1] == subdivisions
        strips = level_indices(7, subdivisions, level).reshape(7, -1)
        assert strips.shape[1] == 6 * (len(rows) - 1)
        for blade, indices in enumerate(strips):
            local = indices.astype(np.int64) - blade * per_blade
            assert set(local // 2) == set(rows)  # whole rows, both sides, of this blade only
        if level + 1 < count:
            finer = set(rows.tolist())
            assert set(level_rows(subdivisions, level + 1).tolist()) <= finer
            assert len(level_rows(subdivisions, level + 1)) - 1 == (len(rows) - 1 + 1) // 2
