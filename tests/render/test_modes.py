"""Frame pipeline modes: compare (three representations side by side) and slices converted
outside the pipeline (the viewport converts step by step)."""

import numpy as np

from app.scenes import get_scene
from core.params import SliceParams
from render.slices import SliceTextures

SCENE = get_scene("patch-grid")
PARAMS = SCENE.params.replace(blade_count=500)
SIZE = (300, 120)


def test_compare_mode_shows_each_representation_in_its_column(headless, ctx):
    headless.load(SCENE, PARAMS)
    headless.pipeline.set_only("compare")
    headless.pipeline.view = "techniques"
    image, stats = headless.render(SCENE.camera("default"), SIZE)
    headless.pipeline.view = "shaded"
    headless.pipeline.set_only("geometry")
    assert (stats.c_g, stats.c_v, stats.c_i) == (64, 64, 64)
    assert stats.t_g_ms > 0 and stats.t_v_ms > 0 and stats.t_i_ms > 0
    r, g, b = (image[..., c].astype(int) for c in range(3))
    colours = {
        "red": (r > 120) & (g < 0.5 * r) & (b < 0.5 * r),
        "yellow": (r > 120) & (g > 0.6 * r) & (b < 0.4 * r),
        "blue": (b > 120) & (r < 0.5 * b) & (g < 0.7 * b),
    }
    thirds = np.array_split(np.arange(SIZE[0]), 3)
    for column, (colour, mask) in zip(thirds, colours.items(), strict=True):
        inside = mask[:, column].mean()
        outside = np.delete(mask, column, axis=1).mean()
        assert inside > 0.1 and outside < 0.01, (colour, inside, outside)


def test_slices_converted_outside_follow_patch_and_parameters(headless, ctx):
    pipeline = headless.pipeline
    pipeline.auto_convert = False
    try:
        patch = headless.load(SCENE, PARAMS)
        pipeline.set_only("volume")
        assert pipeline.needs_slices  # nothing converted yet, and nothing converted by itself
        sp = SliceParams(slices=2, width=64, height=16, top=32)
        pipeline.set_slice_params(sp)
        sliced = pipeline.converter.convert(patch, sp.slices, (sp.width, sp.height), sp.top)
        pipeline.set_slice_textures(SliceTextures.upload(ctx, sliced), patch, sp)
        assert not pipeline.needs_slices
        assert pipeline.volume.slices == 2 and pipeline.image.textures is pipeline.volume.textures
        pipeline.set_slice_params(sp.replace(slices=4))
        assert pipeline.needs_slices  # new parameters: convert again
    finally:
        pipeline.auto_convert = True
        pipeline.set_slice_params(SliceParams())
        pipeline.set_only("geometry")
    assert not pipeline.needs_slices


def test_frame_is_opaque_where_grass_is_partly_covered(headless, ctx):
    """A window composes the viewport by its alpha: every pixel must come out opaque, also
    where alpha-to-coverage or the volume's blending left a fractional alpha."""
    headless.load(SCENE, PARAMS)
    out = headless._target(SIZE)
    for mode in ("geometry", "lod"):
        headless.pipeline.set_only(mode)
        headless.pipeline.render(SCENE.camera("default"), out, SIZE)
        alpha = np.frombuffer(out.read(components=4), np.uint8)[3::4]
        assert alpha.min() == 255, mode
    headless.pipeline.set_only("geometry")
