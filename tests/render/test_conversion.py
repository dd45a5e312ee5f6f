"""Patch conversion into vertical and horizontal slices (thesis 4.2.1)."""

import numpy as np
import pytest

from core.params import PatchParams
from core.patch import generate_patch
from render.conversion import PatchConverter

PARAMS = PatchParams(blade_count=800, subdivisions=3)
SIZE = (128, 32)


@pytest.fixture(scope="module")
def converter(gl_ctx):
    conv = PatchConverter(gl_ctx)
    yield conv
    conv.release()


def covered(layers):
    return (layers.color[..., 3] > 0.5).mean(axis=(1, 2))


def test_slices_hold_colour_normals_and_thresholds(converter, ctx):
    sliced = converter.convert(generate_patch(PARAMS), 4, SIZE, top_size=64)
    assert sliced.x.color.shape == (4, 32, 128, 4) and sliced.top.color.shape == (1, 64, 64, 4)
    for layers in (sliced.x, sliced.z, sliced.top):
        for layer in (layers.color, layers.normal, layers.threshold):
            assert np.all(np.isfinite(layer))
    for layers in (sliced.x, sliced.z):
        assert np.all(covered(layers) > 0.03)  # every slab holds blades
    assert covered(sliced.x).mean() == pytest.approx(covered(sliced.z).mean(), rel=0.35)
    opaque = sliced.x.color[..., 3] > 0.5
    n = sliced.x.normal[opaque]
    assert np.allclose(np.linalg.norm(n, axis=-1), 1.0, atol=0.02)
    t = sliced.x.threshold[opaque]
    assert t.min() > 0.0 and t.max() <= 1.0 and 0.3 < t.mean() < 0.7
    green = sliced.x.color[opaque][:, :3].mean(axis=0)
    assert green[1] > green[0] > green[2]
    # grass stands on the ground: the lowest rows are fuller than the top rows
    rows = (sliced.x.color[..., 3] > 0.5).mean(axis=(0, 2))
    assert rows[:4].mean() > rows[-4:].mean()


def test_clip_planes_split_the_patch_between_slabs(converter, ctx):
    patch = generate_patch(PARAMS)
    one = covered(converter.convert(patch, 1, SIZE, top_size=16).x)[0]
    four = covered(converter.convert(patch, 4, SIZE, top_size=16).x)
    assert np.all(four < 0.8 * one)  # each slab sees only part of the blades


def test_fewer_blades_cover_less_of_the_top_slice(converter, ctx):
    dense = converter.convert(generate_patch(PARAMS), 1, SIZE, top_size=64)
    sparse = converter.convert(generate_patch(PARAMS.replace(blade_count=200)), 1, SIZE, 64)
    assert covered(sparse.top)[0] < 0.7 * covered(dense.top)[0]


def test_slice_textures_keep_the_covered_share_in_every_level(converter, ctx):
    from render.slices import SliceTextures, slice_levels

    sliced = converter.convert(generate_patch(PARAMS), 2, SIZE, top_size=64)
    textures = SliceTextures.upload(ctx, sliced)
    base = float(sliced.x.color[..., 3].mean())
    levels = slice_levels(*SIZE[::-1])
    assert levels == 6  # 32 rows: 32, 16, 8, 4, 2, 1
    assert textures.slices == 2
    for k in range(levels - 2):  # read back what the GPU holds at each level
        # both families in one texture: 2 slices across x, then 2 across z
        w, h = max(SIZE[0] >> k, 1), 4 * max(SIZE[1] >> k, 1)
        raw = np.frombuffer(textures.sides.color.read(level=k), np.uint8).reshape(h, w, 4)
        raw = raw[: h // 2]  # the slices across x
        assert float((raw[..., 3] / 255.0).mean()) == pytest.approx(base, abs=0.01)
        data = np.frombuffer(textures.sides.data.read(level=k), np.uint8).reshape(h, w, 4)
        data = data[: h // 2]
        opaque = raw[..., 3] > 128
        assert 0.25 < data[..., 3][opaque].mean() / 255.0 < 0.75  # thresholds survive the mips
    textures.release()


def test_conversion_steps_report_progress_and_give_the_same_slices(converter, ctx):
    patch = generate_patch(PARAMS)
    steps = converter.steps(patch, 3, SIZE, top_size=32)
    progress = []
    while True:
        try:
            progress.append(next(steps))
        except StopIteration as done:
            sliced = done.value
            break
    assert progress == [(k, 7) for k in range(1, 8)]  # 3 + 3 vertical slices, then the top
    whole = converter.convert(patch, 3, SIZE, top_size=32)
    assert np.array_equal(sliced.x.color, whole.x.color)
    assert np.array_equal(sliced.top.threshold, whole.top.threshold)


def test_frames_drawn_between_the_steps_leave_the_slices_as_they_are(converter, headless):
    """The draft process converts a capture at a time and draws the drafts asked for
    meanwhile (render/render_server.py refine_one): those frames bind their own targets and
    state, and the slices must come out as from one conversion."""
    from app.scenes import get_scene

    document = get_scene("patch-grid").document()
    camera = document.camera()
    renderer = headless(document)
    patch = generate_patch(PARAMS)
    steps = converter.steps(patch, 3, SIZE, top_size=32)
    while True:
        renderer.render(camera, (64, 48), half_resolution=True)  # a draft between two captures
        try:
            next(steps)
        except StopIteration as done:
            sliced = done.value
            break
    whole = converter.convert(patch, 3, SIZE, top_size=32)
    for interrupted, plain in ((sliced.x, whole.x), (sliced.z, whole.z), (sliced.top, whole.top)):
        assert np.array_equal(interrupted.color, plain.color)
        assert np.array_equal(interrupted.threshold, plain.threshold)


def test_the_top_view_covers_what_the_blades_cover_at_any_size(converter):
    """The blade's mask is read at its base level: a leaning blade seen from above is
    foreshortened along its length, and read through the mip chain its mask blurred, so the
    top view covered less the coarser it was captured (the blades' own cover is one figure)."""
    patch = generate_patch(PARAMS)
    cover = [
        float(converter.convert(patch, 1, SIZE, top_size=size).top.color[..., 3].mean())
        for size in (64, 512)
    ]
    assert 0.2 < cover[1] < 0.95
    assert cover[0] == pytest.approx(cover[1], abs=0.015)
