"""Frame pipeline modes: compare (three representations side by side) and slices converted
outside the pipeline (the viewport converts step by step)."""

import dataclasses

import numpy as np

from app.scenes import get_scene
from core.params import SliceParams
from render.binding import DocumentBinding
from render.frame import FramePipeline
from render.slices import SliceTextures

SCENE = get_scene("patch-grid")
PARAMS = SCENE.params.replace(blade_count=500)
SIZE = (300, 120)


def document():
    return dataclasses.replace(SCENE, params=PARAMS).document()


def test_compare_mode_shows_each_representation_in_its_column(headless):
    doc = document()
    renderer = headless(doc, mode="compare", view="techniques")
    image, stats = renderer.render(doc.camera("default"), SIZE)
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


def test_slices_converted_outside_follow_patch_and_parameters(ctx):
    pipeline = FramePipeline(ctx)
    pipeline.auto_convert = False  # as in the viewport, which converts step by step
    pipeline.set_mode("volume")
    doc = document()
    binding = DocumentBinding(pipeline, doc)
    try:
        patch = pipeline.grass_types[0].patch
        assert pipeline.needs_slices  # nothing converted yet, and nothing converted by itself
        sp = SliceParams(slices=2, width=64, height=16, top=32)
        doc.slices = sp
        sliced = pipeline.converter.convert(patch, sp.slices, (sp.width, sp.height), sp.top)
        pipeline.set_slice_textures(SliceTextures.upload(ctx, sliced), patch, sp)
        assert not pipeline.needs_slices
        first = pipeline.grass_types[0]
        assert first.volume(2).slices == 2 and first.image.textures is first.volume(2).textures
        doc.slices = sp.replace(slices=4)
        assert pipeline.needs_slices  # new parameters: convert again
    finally:
        binding.detach()
        pipeline.release()


def test_frame_is_opaque_where_grass_is_partly_covered(headless):
    """A window composes the viewport by its alpha: every pixel must come out opaque, also
    where alpha-to-coverage or the volume's blending left a fractional alpha."""
    doc = document()
    for mode in ("geometry", "lod"):
        image, _ = headless(doc, mode=mode).render(doc.camera("default"), SIZE, alpha=True)
        assert image[..., 3].min() == 255, mode
