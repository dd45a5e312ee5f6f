"""The facing-lambert table of one grass type on the GPU (core/facing.py): a small float
texture over the azimuth and elevation of the direction to the viewer, rebuilt when the patch or
the light changes. The volume and image-based shaders light with it (shaders/_lighting.glsl).
Its lower half holds L, G_x and G_z, its upper half H_xx, H_xz and H_zz: how the light changes
as the wind bends the blades (core/facing.py bend_coefficients)."""

from __future__ import annotations

import hashlib
import weakref
from collections import OrderedDict
from collections.abc import Callable

import moderngl
import numpy as np

from core.canopy import Canopy
from core.facing import AZIMUTHS, ELEVATIONS, bend_coefficients, bend_moments, facing_moments
from core.light_moments import LightMoments, light_coefficients
from core.lighting import Lighting
from core.patch import GrassPatch
from core.slopes import ACROSS, SLOPES, SlopeMoments, slope_moments_table, slope_ratios
from render import derived_cache

FACING_UNIT = 6  # texture unit of the table (render/uniforms.py has the others)
SLOPE_UNIT = 12  # texture unit of the slope-ratio table
KEPT_TABLES = 8  # sums kept by the patch and canopy they are of (each a build of its own)
_kept: OrderedDict[str, SlopeMoments] = OrderedDict()
_kept_facing: OrderedDict[str, LightMoments] = OrderedDict()


_vertex_digests: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # patch -> its hash


def _digest(patch: GrassPatch, canopy: Canopy | None) -> str:
    """The content of a patch and canopy: sums kept by it stand in for no other. A patch's
    vertices are hashed once (a frame asks for a patch's sums with and without its canopy)."""
    vertices = _vertex_digests.get(patch)
    if vertices is None:
        vertices = hashlib.blake2b(patch.vertices.tobytes(), digest_size=16)
        _vertex_digests[patch] = vertices
    digest = vertices.copy()
    if canopy is not None:
        for sigma, colour in canopy.profiles:
            digest.update(np.ascontiguousarray(sigma).tobytes())
            digest.update(np.ascontiguousarray(colour).tobytes())
        digest.update(np.float64(canopy.height).tobytes())
    return digest.hexdigest()


def read_ahead(patch: GrassPatch, canopy: Canopy) -> None:
    """Begin reading the sums a grass type of this patch and canopy lights with, if kept
    (render/derived_cache.py read_ahead): its slope sums and its facing sums with and without
    the canopy."""
    for kind, seen in (("slope", canopy), ("facing", None), ("facing", canopy)):
        key = _digest(patch, seen)
        if key not in (_kept if kind == "slope" else _kept_facing):
            derived_cache.read_ahead(kind, key)
    derived_cache.beside(light_coefficients, (0.0, 1.0, 0.0))  # its fit, made once a process


def _keep(kept: OrderedDict, key: str, value) -> None:
    kept[key] = value
    kept.move_to_end(key)
    while len(kept) > KEPT_TABLES:
        kept.popitem(last=False)


def kept_slope_moments(
    patch: GrassPatch, canopy: Canopy, build: bool = True, wait: bool = True
) -> SlopeMoments | None:
    """core/slopes.py slope_moments_table of this patch and canopy, the last KEPT_TABLES kept:
    each renderer of a grass type has its own SlopeTable (the quality run's two, the draft's
    and the full frame's, every test's), a build takes a quarter of a second, and every light is a
    small product of the same sums (core/light_moments.py). Sums built before, here, by the
    designer's other render process or in an earlier run, are read from the folder kept for
    them (render/derived_cache.py). None if they are not there and not `build`, or another
    process is building them and not `wait`."""
    key = _digest(patch, canopy)
    moments = _kept.get(key)
    if moments is None:
        if build:

            def made() -> SlopeMoments:
                v = patch.vertices
                return slope_moments_table(v["normal"], v["position"], v["root"], canopy)

            moments = derived_cache.fetch("slope", key, made, wait)
        else:
            moments = derived_cache.load("slope", key)
        if moments is None:
            return None
    _keep(_kept, key, moments)
    return moments


def kept_facing_moments(
    patch: GrassPatch, canopy: Canopy | None, wait: bool = True
) -> LightMoments | None:
    """core/facing.py facing_moments of this patch (each vertex seen through `canopy` where
    given), the last KEPT_TABLES kept by content (an undo or redo of a blade edit brings back
    a patch whose sums were built before), and handed between processes and runs as the slope
    sums are (render/derived_cache.py). None while another process builds them and not `wait`."""
    key = _digest(patch, canopy)
    moments = _kept_facing.get(key)
    if moments is None:

        def made() -> LightMoments:
            v = patch.vertices
            seen = None if canopy is None else (v["position"][:, 1], canopy)
            return facing_moments(v["normal"], seen=seen)

        moments = derived_cache.fetch("facing", key, made, wait)
        if moments is None:
            return None
    _keep(_kept_facing, key, moments)
    return moments


class FacingTable:
    """`canopy`: where given, each blade vertex counts as far as a view reaches it through the
    blades above (core/facing.py `seen`): what the image-based grass, one slice for the whole
    canopy, must show; the volume's samples are occluded by the ray itself."""

    def __init__(
        self,
        ctx: moderngl.Context,
        patch: Callable[[], GrassPatch | None],
        canopy: Callable[[], Canopy | None] | None = None,
    ) -> None:
        self.ctx = ctx
        self._patch = patch
        self._canopy = canopy
        self.texture = ctx.texture((AZIMUTHS, 2 * ELEVATIONS), 3, dtype="f4")
        self.texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.texture.repeat_x = True  # azimuth wraps
        self.texture.repeat_y = False
        self._used: tuple | None = None  # the patch, light, canopy and bend the table is of
        # the patch's sums for any light (core/light_moments.py): the patch and canopy they are
        # of, the table at rest, the bent tables (None until the wind asks for them)
        self._moments: tuple | None = None

    def moments(self, bend: bool, draft: bool = False, wait: bool = True) -> tuple | None:
        """(patch, canopy, the sums at rest, the bent sums or None): the sums of the patch and
        canopy they name, built when those change, or the bent ones when first needed; a light
        change uses them as they are. In a draft the sums held stand in for a new patch's until
        the full frame (a blade edit's draft does not wait for them). Not `wait`: the sums held
        (None if none) while another process builds the new ones."""
        patch = self._patch()
        if patch is None:
            return None
        canopy = self._canopy() if self._canopy is not None else None
        held = self._moments
        stale = held is None or held[0] is not patch or held[1] is not canopy
        if held is None or (stale and not draft):
            sums = kept_facing_moments(patch, canopy, wait)
            if sums is None:
                return held
            held = self._moments = (patch, canopy, sums, None)
        if bend and held[3] is None and (held[0] is patch or not draft):
            held = self._moments = (*held[:3], bend_moments(held[0].vertices, held[1]))
        return held

    def stale(self) -> bool:
        """Whether the sums held are of another patch or canopy than the grass type's now (a
        draft drew with them: refresh before the frames that follow)."""
        held = self._moments
        canopy = self._canopy() if self._canopy is not None else None
        return held is not None and (held[0] is not self._patch() or held[1] is not canopy)

    def refresh(self, wait: bool = True) -> None:
        """Build or find the sums of the patch and canopy as they are now (the bent ones if
        held); not `wait`: unless another process is building them (stale says so after)."""
        self.moments(self._moments is not None and self._moments[3] is not None, wait=wait)

    @staticmethod
    def _rows(held: tuple, lighting: Lighting, bend: bool) -> np.ndarray:
        _patch, _canopy, rest_sums, bent_sums = held
        light, through = lighting.sun_direction, lighting.translucency
        rest = rest_sums.lit(light, through).astype(np.float32)
        if bend and bent_sums is not None:
            coefficients = bend_coefficients(None, light, through, moments=bent_sums)
        else:
            coefficients = np.zeros((*rest.shape, 5), np.float32)
        return np.concatenate([np.dstack([rest, coefficients[..., :2]]), coefficients[..., 2:]])

    def table(self, lighting: Lighting, bend: bool = True) -> np.ndarray | None:
        """(2 · ELEVATIONS, AZIMUTHS, 3): the texture's rows; the bend coefficients zero
        unless `bend`."""
        held = self.moments(bend)
        return None if held is None else self._rows(held, lighting, bend)

    def use(
        self, lighting: Lighting, wind: bool = False, unit: int = FACING_UNIT, draft: bool = False
    ) -> None:
        """Bind the table of the grass type's patch and this light; `wind`: with the bend
        coefficients, which still air does not read (they cost twice the rest); `draft`: the
        sums held may stand in for a new patch's (moments)."""
        held = self.moments(wind, draft)
        if held is not None:
            light = (*lighting.sun_direction, lighting.translucency)
            key = (held[0], held[1], light, wind and held[3] is not None)
            used = self._used
            if (
                used is None
                or any(a is not b for a, b in zip(used[:2], key[:2], strict=True))
                or used[2:] != key[2:]
            ):
                self.texture.write(np.ascontiguousarray(self._rows(held, lighting, wind)).tobytes())
                self._used = key
        self.texture.use(unit)

    def release(self) -> None:
        self.texture.release()


class SlopeTable:
    """The slope-ratio tables of one grass type (core/slopes.py slope_tables), by view direction,
    elevation over the ground and the ground's rise across the view: upright blades on sloping
    ground against the sheared slices (red: the volume multiplies its diffuse factor by it) and
    against upright blades on flat ground (green: the image-based grass, lit by the flat
    ground's facing table); one 3D float texture (shaders/_lighting.glsl slope_ratios), ones
    until the grass type has slices (its canopy), rewritten when the patch, the canopy or the
    light changes, from the sums kept_slope_moments keeps. The image-based grass takes the
    flat-ground ratio, not the volume's: it is lit by the flat ground's facing table."""

    def __init__(
        self,
        ctx: moderngl.Context,
        patch: Callable[[], GrassPatch | None],
        canopy: Callable[[], Canopy | None],
    ) -> None:
        self._patch, self._canopy = patch, canopy
        # the blocks of the ground's rise across the view one after another along z
        self.texture = ctx.texture3d((AZIMUTHS, ELEVATIONS, SLOPES * ACROSS), 2, dtype="f4")
        self.texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.texture.repeat_x = True  # azimuth wraps
        self.texture.repeat_y = False  # z repeats: a block is read between its end texels' centres
        self._ones = np.ones((ACROSS, SLOPES, ELEVATIONS, AZIMUTHS, 2), np.float32)
        self.texture.write(self._ones.tobytes())
        self._used: tuple | None = None  # the sums and light the texture is of
        self._sums: tuple | None = None  # (patch, canopy, their kept sums)
        self._lacking = False  # a draft drew with ones for want of sums

    def stale(self) -> bool:
        """Whether a draft left sums of another patch or canopy held (FacingTable.stale), or
        drew with none (the tables' ones) for want of them."""
        held, patch, canopy = self._sums, self._patch(), self._canopy()
        if patch is None or canopy is None:
            return False
        if held is None:
            return self._lacking
        return held[0] is not patch or held[1] is not canopy

    def refresh(self, wait: bool = True) -> None:
        """Build or find the sums of the patch and canopy as they are now; not `wait`: unless
        another process is building them (stale says so after)."""
        patch, canopy = self._patch(), self._canopy()
        if patch is not None and canopy is not None:
            sums = kept_slope_moments(patch, canopy, wait=wait)
            if sums is not None:
                self._sums = (patch, canopy, sums)
                self._lacking = False

    def use(self, lighting: Lighting, unit: int = SLOPE_UNIT, draft: bool = False) -> None:
        """Bind the tables of the grass type's patch, canopy and this light; `draft`: the sums
        held stand in for a new patch's that are not built yet (as FacingTable.moments), and
        with none held the tables are ones (no slope's change of light) until they are."""
        patch, canopy = self._patch(), self._canopy()
        if patch is not None and canopy is not None:
            held = self._sums
            if held is None or held[0] is not patch or held[1] is not canopy:
                sums = kept_slope_moments(patch, canopy, build=not draft)
                if sums is not None:
                    held = self._sums = (patch, canopy, sums)
                    self._lacking = False
            if held is None:
                self._lacking = True
                if self._used is not None:
                    self.texture.write(self._ones.tobytes())
                    self._used = None
            else:
                light = (*lighting.sun_direction, lighting.translucency)
                old = self._used
                if old is None or old[0] is not held[2] or old[1] != light:
                    table = slope_ratios(held[2], lighting.sun_direction, lighting.translucency)
                    self.texture.write(np.ascontiguousarray(table).tobytes())
                    self._used = (held[2], light)
        self.texture.use(unit)

    def release(self) -> None:
        self.texture.release()


def bind_slopes(
    program: moderngl.Program, table: SlopeTable | None, lighting: Lighting, draft: bool = False
) -> None:
    """Point a far representation's program at its grass type's slope tables (or tell it there
    are none). The sampler keeps its own unit even without a table: two sampler types on one
    unit are an invalid operation."""
    program["u_slope_ratio"].value = SLOPE_UNIT
    program["u_slopes"].value = table is not None
    if table is not None:
        table.use(lighting, draft=draft)
