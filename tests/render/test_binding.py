"""The one binding from the document to a frame pipeline: fully synchronised when attached,
then every change of the document reaches the pipeline, and nothing after it is detached."""

import dataclasses

from app.scenes import get_scene
from core.lighting import Lighting
from core.lod import LodConfig
from core.params import SliceParams
from render.binding import DocumentBinding
from render.frame import FramePipeline

SCENE = get_scene("meadow")


def document():
    return dataclasses.replace(SCENE, params=SCENE.params.replace(blade_count=200)).document()


def test_attaching_synchronises_every_grass_type_and_the_scene(ctx):
    doc = document()
    pipeline = FramePipeline(ctx)
    binding = DocumentBinding(pipeline, doc)
    try:
        assert [k.lod for k in pipeline.grass_types] == [k.lod for k in doc.grass_types]
        assert [k.density_channel for k in pipeline.grass_types] == [0, 1]
        assert [k.patch.params for k in pipeline.grass_types] == [k.params for k in doc.grass_types]
        assert pipeline.terrain is doc.terrain and pipeline.map_textures.maps is doc.maps
        assert pipeline.light == doc.light and pipeline.slice_params == doc.slices
        assert pipeline.props.count == len(doc.props)
    finally:
        binding.detach()
        pipeline.release()


def test_each_change_reaches_the_pipeline_and_nothing_after_detach(ctx):
    doc = document()
    pipeline = FramePipeline(ctx)
    pipeline.auto_convert = False
    binding = DocumentBinding(pipeline, doc)
    try:
        doc.density = 0.4
        assert pipeline.grass_types[0].geometry.density == 0.4
        lod = LodConfig.zones(geometry_end=2.0, volume_end=9.0)
        doc.set_lod(1, lod)
        assert pipeline.grass_types[1].lod == lod
        doc.set_params(0, doc.params(0).replace(blade_count=50))
        assert pipeline.grass_types[0].patch.params.blade_count == 50
        doc.light = Lighting(sun_elevation=12.0)
        assert pipeline.light.sun_elevation == 12.0
        doc.slices = SliceParams(slices=2)
        assert pipeline.slice_params.slices == 2
        doc.maps.fill("height", 0.5)
        new = doc.rebuild_terrain()
        assert pipeline.terrain is new
        binding.detach()
        doc.density = 0.9
        assert pipeline.grass_types[0].geometry.density == 0.4
    finally:
        pipeline.release()
