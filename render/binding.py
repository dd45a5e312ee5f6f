"""The one binding from the document (core/document.py) to a frame pipeline: it synchronises
the pipeline fully when attached and then follows the document's events, so nothing else copies
document state into the renderer (the command line, the tests, the benchmarks and the render
processes behind the designer's viewport all draw through it). The design maps need no event
here: their GL mirror uploads each edited rectangle at the next frame (render/design_maps.py)."""

from __future__ import annotations

from core.document import Document
from core.lighting import Lighting
from core.lod import LodConfig
from core.params import PatchParams, SliceParams
from core.patch import generate_patch
from core.terrain import Terrain
from core.wind import Wind
from render.frame import FramePipeline


class DocumentBinding:
    def __init__(self, pipeline: FramePipeline, document: Document) -> None:
        self.pipeline = pipeline
        self.document = document
        self._handlers = {
            "params": self._on_params,
            "lod": self._on_lod,
            "density": self._on_density,
            "slices": self._on_slices,
            "light": self._on_light,
            "terrain": self._on_terrain,
            "props": self._on_props,
            "wind": self._on_wind,
        }
        self._fully_synchronize()
        for name, handler in self._handlers.items():
            getattr(document.events, name).connect(handler)

    def _fully_synchronize(self) -> None:
        d, p = self.document, self.pipeline
        p.set_slice_params(d.slices)
        p.set_grass_types([(grass.lod, grass.channel) for grass in d.grass_types])
        p.set_terrain(d.terrain)
        p.set_design_maps(d.maps)
        p.set_props(d.prop_boxes())
        p.light = d.light
        p.wind = d.wind
        p.set_density(d.density)
        for index, grass in enumerate(d.grass_types):
            p.set_patch(index, generate_patch(grass.params))

    def detach(self) -> None:
        for name, handler in self._handlers.items():
            getattr(self.document.events, name).disconnect(handler)

    # -- events ------------------------------------------------------------------------------
    def _on_params(self, index: int, params: PatchParams) -> None:
        self.pipeline.set_patch(index, generate_patch(params))

    def _on_lod(self, index: int, lod: LodConfig) -> None:
        self.pipeline.set_lod(index, lod)

    def _on_density(self, density: float) -> None:
        self.pipeline.set_density(density)

    def _on_slices(self, slices: SliceParams) -> None:
        self.pipeline.set_slice_params(slices)

    def _on_light(self, light: Lighting) -> None:
        self.pipeline.light = light

    def _on_wind(self, wind: Wind) -> None:
        self.pipeline.wind = wind

    def _on_terrain(self, terrain: Terrain) -> None:
        self.pipeline.set_terrain(terrain)
        self._on_props()  # props stand on the ground as it is now

    def _on_props(self, _props: object = None) -> None:
        self.pipeline.set_props(self.document.prop_boxes())
