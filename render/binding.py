"""The one binding from the document (core/document.py) to a frame pipeline: it synchronises
the pipeline fully when attached and then follows the document's events, so nothing else copies
document state into the renderer (the command line, the tests, the benchmarks and the designer's
viewport all draw through it)."""

from __future__ import annotations

import contextlib
from collections.abc import Callable

from core.document import Document
from core.params import PatchParams
from core.patch import GrassPatch, generate_patch
from render.frame import FramePipeline

# asks for grass type i's patch to be made (off the window's thread); None: made here, at once
PatchRequest = Callable[[int, PatchParams], None]


class DocumentBinding:
    def __init__(
        self,
        pipeline: FramePipeline,
        document: Document,
        request_patch: PatchRequest | None = None,
        current: Callable[[], contextlib.AbstractContextManager] | None = None,
        changed: Callable[[], None] | None = None,
    ) -> None:
        """`current` makes the pipeline's GL context current around each change (the viewport's
        makeCurrent / doneCurrent); `changed` is called after each (a new frame is due)."""
        self.pipeline = pipeline
        self.document = document
        self._request = request_patch
        self.current = current or contextlib.nullcontext
        self.changed = changed or (lambda: None)
        self._handlers = {
            "params": self._on_params,
            "lod": self._on_lod,
            "density": self._on_density,
            "slices": self._on_slices,
            "light": self._on_light,
            "terrain": self._on_terrain,
        }
        with self.current():
            self._fully_synchronize()
        for name, handler in self._handlers.items():
            getattr(document.events, name).connect(handler)
        # the map textures upload their dirty rectangles at the next frame by themselves
        # (render/design_maps.py); an edit, an undo or an import only needs that frame
        document.maps.changed.connect(self._on_maps_changed)

    def _fully_synchronize(self) -> None:
        d, p = self.document, self.pipeline
        p.set_slice_params(d.slices)
        p.set_grass_types([(grass.lod, grass.channel) for grass in d.grass_types])
        p.set_terrain(d.terrain)
        p.set_design_maps(d.maps)
        p.set_props(d.prop_boxes())
        p.lighting = d.light
        p.set_density(d.density)
        for index, grass in enumerate(d.grass_types):
            self._patch_for(index, grass.params)

    def _patch_for(self, index: int, params: PatchParams) -> None:
        if self._request is None:
            self.pipeline.set_patch(index, generate_patch(params))
        else:
            self._request(index, params)

    def set_patch(self, index: int, patch: GrassPatch) -> None:
        """A patch made elsewhere for grass type `index` (the designer's patch builder)."""
        if patch.params != self.document.params(index):
            return  # made for parameters the document no longer has
        with self.current():
            self.pipeline.set_patch(index, patch)
        self.changed()

    def detach(self) -> None:
        for name, handler in self._handlers.items():
            getattr(self.document.events, name).disconnect(handler)
        self.document.maps.changed.disconnect(self._on_maps_changed)

    # -- events ------------------------------------------------------------------------------
    def _apply(self, fn: Callable[[], object]) -> None:
        with self.current():
            fn()
        self.changed()

    def _on_params(self, index: int, params: PatchParams) -> None:
        if self._request is not None:
            self._request(index, params)
        else:
            self._apply(lambda: self.pipeline.set_patch(index, generate_patch(params)))

    def _on_lod(self, index: int, lod) -> None:
        self._apply(lambda: self.pipeline.set_lod(index, lod))

    def _on_density(self, density: float) -> None:
        self._apply(lambda: self.pipeline.set_density(density))

    def _on_slices(self, slices) -> None:
        self._apply(lambda: self.pipeline.set_slice_params(slices))

    def _on_light(self, light) -> None:
        def set_light() -> None:
            self.pipeline.lighting = light

        self._apply(set_light)

    def _on_maps_changed(self, _name: str, _rect) -> None:
        self.changed()

    def _on_terrain(self, terrain) -> None:
        self._apply(lambda: self.pipeline.set_terrain(terrain))
