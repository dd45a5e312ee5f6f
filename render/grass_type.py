"""One grass type on the terrain (thesis 6.4.5): its patch, its slices, its LOD levels and the
renderers that draw it. The frame pipeline draws one renderer set per grass type over the shared
terrain, ground and design maps; each reads its own channel of the density map."""

from __future__ import annotations

import moderngl
import numpy as np

from core.canopy import Canopy
from core.draw_list import DrawList
from core.grid import INSTANCE_DTYPE
from core.lod import NO_FADE, LodConfig
from core.occupancy import DensityOccupancy
from core.params import SliceParams
from core.patch import GrassPatch
from core.terrain import Terrain
from render.conversion import PatchConverter
from render.facing import FacingTable, SlopeTable, read_ahead
from render.geometry import GeometryRenderer
from render.image import ImageRenderer
from render.slices import SliceTextures
from render.volume import VolumeRenderer, carriers


def technique_colors() -> dict[str, list[tuple[float, float, float]]]:
    """The colours the technique view draws each representation's levels in (core/quality.py
    tells the regions apart by them)."""
    return {
        "geometry": [GeometryRenderer.technique_color],
        "volume": [volume_technique_color(n) for n in (1, 2, 4, 8, 16)],
        "image": [ImageRenderer.technique_color],
    }


def volume_technique_color(slices: int) -> tuple[float, float, float]:
    """Volume levels are yellow in the technique view (thesis Figs. 7.1-7.6); levels with fewer
    slices in lighter or deeper yellows, so the thesis's three volume levels can be told apart."""
    if slices >= 8:
        return (1.0, 0.85, 0.1)
    if slices >= 2:
        return (0.95, 0.62, 0.05)
    return (1.0, 0.97, 0.38)


class GrassTypeRenderer:
    def __init__(self, ctx: moderngl.Context, density_channel: int = 0) -> None:
        self.ctx = ctx
        self.density_channel = density_channel
        self.geometry = GeometryRenderer(ctx)
        self.volumes: dict[int, VolumeRenderer] = {}  # one per slice count (thesis ch. 7)
        self.image = ImageRenderer(ctx)
        # the blades' mean diffuse factor by view direction: the volumes' (set below); the
        # image-based grass has its own, of the blade parts a view reaches (render/facing.py)
        self.facing = FacingTable(ctx, lambda: self.patch)
        self.image.facing = FacingTable(ctx, lambda: self.patch, self._canopy)
        # upright blades on slopes against the sheared slices (the volumes) and against flat
        # ground (the image-based grass): render/facing.py
        self.slope = SlopeTable(ctx, lambda: self.patch, self._canopy)
        self.image.slope = self.slope
        self.lod = LodConfig()
        self._slices: dict[int, SliceTextures] = {}  # by slice count, one patch, one size
        self._slices_source: tuple[GrassPatch, tuple[int, int, int]] | None = None
        self._instances = np.zeros(0, INSTANCE_DTYPE)
        self._set_channel(self.geometry)
        self._set_channel(self.image)

    def stale_light_sums(self) -> bool:
        """Whether a draft drew with the light sums of the patch before an edit (or none)."""
        return any(t.stale() for t in (self.facing, self.image.facing, self.slope) if t)

    def refresh_light_sums(self, wait: bool = True) -> None:
        """Build or find the light sums of the patch now; not `wait`: those another process is
        building stay stale until it has."""
        for table in (self.facing, self.image.facing, self.slope):
            if table is not None:
                table.refresh(wait)

    def _set_channel(self, renderer) -> None:
        renderer.density_channel = self.density_channel

    def _canopy(self) -> Canopy | None:
        t = self.image.textures
        return None if t is None else t.canopy

    @property
    def patch(self) -> GrassPatch | None:
        return self.geometry.patch

    @property
    def renderers(self) -> list:
        return [self.geometry, self.image, *self.volumes.values()]

    def volume(self, slices: int) -> VolumeRenderer:
        if slices not in self.volumes:
            renderer = VolumeRenderer(self.ctx)
            renderer.technique_color = volume_technique_color(slices)
            renderer.density = self.geometry.density
            renderer.facing = self.facing
            renderer.slope = self.slope
            self._set_channel(renderer)
            renderer.set_instances(self._instances)
            if slices in self._slices:
                renderer.set_slices(self._slices[slices], owned=False)
            self.volumes[slices] = renderer
        return self.volumes[slices]

    def set_instances(self, instances: np.ndarray) -> None:
        self._instances = instances
        for renderer in self.renderers:
            renderer.set_instances(instances)

    def set_density(self, density: float) -> None:
        for renderer in self.renderers:
            renderer.density = float(density)

    # -- slices ------------------------------------------------------------------------------
    def required_slices(self, mode: str, sp: SliceParams) -> list[int]:
        """Slice counts the mode draws this grass type with."""
        if mode == "geometry" or self.patch is None:
            return []
        if mode == "lod":
            counts = {lv.slices for lv in self.lod.levels if lv.representation == "volume"}
            if not counts and "image" in self.lod.representations():
                counts = {sp.slices}  # the image-based needs a top slice
            return sorted(counts)
        return [sp.slices]

    def missing_slices(self, mode: str, sp: SliceParams) -> list[int]:
        """Slice counts needed now whose textures do not exist for this patch and these sizes."""
        if self._slices_source != (self.patch, (sp.width, sp.height, sp.top)):
            return self.required_slices(mode, sp)
        return [n for n in self.required_slices(mode, sp) if n not in self._slices]

    def set_slice_textures(
        self, textures: SliceTextures, patch: GrassPatch, params: SliceParams, image_slices: int
    ) -> None:
        """Slices converted for `patch` with `params`; the image-based renderer takes the top
        slice of the `image_slices` conversion when there is one."""
        source = (patch, (params.width, params.height, params.top))
        old = self._slices_source
        if old is None or old[0] is not patch or old[1] != source[1]:
            for stale in self._slices.values():
                stale.release()
            self._slices = {}
            self._slices_source = source
        if params.slices in self._slices:
            self._slices[params.slices].release()
        self._slices[params.slices] = textures
        for n, renderer in self.volumes.items():
            renderer.set_slices(self._slices.get(n), owned=False)
        self.image.textures = self._slices.get(image_slices, textures)

    def convert(self, converter: PatchConverter, mode: str, sp: SliceParams) -> None:
        for n in self.missing_slices(mode, sp):
            patch = self.patch
            assert patch is not None
            sliced = converter.convert(patch, n, (sp.width, sp.height), sp.top)
            textures = SliceTextures.upload(self.ctx, sliced)
            self.set_slice_textures(textures, patch, sp.replace(slices=n), sp.slices)
            canopy = self._canopy()
            if canopy is not None:  # the light sums its first frame asks for
                read_ahead(patch, canopy)

    # -- drawing -----------------------------------------------------------------------------
    def upload(
        self,
        cells: DrawList,
        eye: np.ndarray | None = None,
        terrain: Terrain | None = None,
        occupancy: DensityOccupancy | None = None,
    ) -> dict[tuple[str, int], tuple[object, int]]:
        """Hand each renderer its cells (one instance upload each): (representation, slices)
        -> (renderer, instance count). `eye`: the volume's cells go far to near from it;
        `terrain`: their cuboids follow its ground's slope (Terrain.planes_of) and, with
        `occupancy`, keep to the cells where this type can grow (DensityOccupancy.rects)."""
        batches = {}
        for key, instances in cells.batches.items():
            representation, n = key
            renderer = {"geometry": self.geometry, "image": self.image}.get(representation)
            if renderer is None:
                renderer = self.volume(n)
                far = np.zeros(instances.size)
                if eye is not None and instances.size:  # far to near: blended in that order
                    centre = instances["origin"] + 0.5 * instances["size"]
                    far = np.hypot(centre[:, 0] - eye[0], centre[:, 1] - eye[2])
                    order = np.argsort(-far, kind="stable")
                    instances, far = instances[order], far[order]
                renderer.cells, renderer.distances = instances, far  # uploaded by distance band
                renderer.carrier_rows = None
                if terrain is not None:
                    renderer.carrier_rows = carriers(
                        terrain, occupancy, self.density_channel, instances
                    )
            elif representation == "image":
                rects = None
                if terrain is not None and occupancy is not None and instances.size:
                    blocks = terrain.blocks_of(instances)
                    rects = occupancy.rects(self.density_channel, *blocks)
                renderer.set_instances(instances, rects)
            else:
                renderer.set_instances(instances)
            if representation != "geometry":  # blades stand in single cells: their own w
                renderer.fade = cells.fades.get(key, NO_FADE)
            batches[key] = (renderer, int(instances.size))
        return batches

    def release(self) -> None:
        for renderer in self.renderers:
            renderer.release()
        for textures in self._slices.values():
            textures.release()
        self._slices = {}
        self.facing.release()
        self.slope.release()
        if self.image.facing is not None:
            self.image.facing.release()
