"""The facing-lambert table of one grass type on the GPU (core/facing.py): a small float
texture over the azimuth and elevation of the direction to the viewer, rebuilt when the patch or
the light changes. The volume and image-based shaders light with it (shaders/_lighting.glsl).
Its lower half holds L, G_x and G_z, its upper half H_xx, H_xz and H_zz: how the light changes
as the wind bends the blades (core/facing.py bend_coefficients)."""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Callable

import moderngl
import numpy as np

from core.canopy import Canopy
from core.facing import (
    ACROSS,
    AZIMUTHS,
    ELEVATIONS,
    SLOPES,
    SlopeMoments,
    bend_coefficients,
    bend_moments,
    facing_moments,
    slope_moments_table,
    slope_ratios,
)
from core.light_moments import LightMoments
from core.lighting import Lighting
from core.patch import GrassPatch

FACING_UNIT = 6  # texture unit of the table (render/uniforms.py has the others)
SLOPE_UNIT = 12  # texture unit of the slope-ratio table
KEPT_TABLES = 8  # slope-table sums kept by the patch and canopy they are of (a build: a second)
_kept: OrderedDict[tuple, SlopeMoments] = OrderedDict()


def kept_slope_moments(patch: GrassPatch, canopy: Canopy) -> SlopeMoments:
    """core/facing.py slope_moments_table of this patch and canopy, the last KEPT_TABLES kept:
    each renderer of a grass type has its own SlopeTable (the quality run's two, the draft's
    and the full frame's, every test's), a build takes about a second, and every light is a
    small product of the same sums (core/light_moments.py)."""
    digest = hashlib.blake2b(patch.vertices.tobytes(), digest_size=16)
    for sigma, colour in canopy.profiles:
        digest.update(np.ascontiguousarray(sigma).tobytes())
        digest.update(np.ascontiguousarray(colour).tobytes())
    key = (digest.digest(), canopy.height)
    moments = _kept.get(key)
    if moments is None:
        v = patch.vertices
        moments = slope_moments_table(v["normal"], v["position"], v["root"], canopy)
        _kept[key] = moments
        while len(_kept) > KEPT_TABLES:
            _kept.popitem(last=False)
    _kept.move_to_end(key)
    return moments


def kept_slope_tables(patch: GrassPatch, canopy: Canopy, lighting: Lighting) -> np.ndarray:
    """core/facing.py slope_tables of this patch, canopy and light, from the kept sums."""
    moments = kept_slope_moments(patch, canopy)
    return slope_ratios(moments, lighting.sun_direction, lighting.translucency)


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

    def moments(self, bend: bool) -> tuple[LightMoments, LightMoments | None] | None:
        """The patch's sums (at rest, bent): built when the patch or canopy changes, or when
        the bent ones are first needed; a light change uses them as they are."""
        patch = self._patch()
        if patch is None:
            return None
        canopy = self._canopy() if self._canopy is not None else None
        held = self._moments
        if held is None or held[0] is not patch or held[1] is not canopy:
            v = patch.vertices
            seen = None if canopy is None else (v["position"][:, 1], canopy)
            held = self._moments = (patch, canopy, facing_moments(v["normal"], seen=seen), None)
        if bend and held[3] is None:
            held = self._moments = (*held[:3], bend_moments(patch.vertices, canopy))
        return held[2], held[3]

    def table(self, lighting: Lighting, bend: bool = True) -> np.ndarray | None:
        """(2 · ELEVATIONS, AZIMUTHS, 3): the texture's rows; the bend coefficients zero
        unless `bend`."""
        sums = self.moments(bend)
        if sums is None:
            return None
        rest_sums, bent_sums = sums
        light, through = lighting.sun_direction, lighting.translucency
        rest = rest_sums.lit(light, through).astype(np.float32)
        if bend and bent_sums is not None:
            coefficients = bend_coefficients(None, light, through, moments=bent_sums)
        else:
            coefficients = np.zeros((*rest.shape, 5), np.float32)
        return np.concatenate([np.dstack([rest, coefficients[..., :2]]), coefficients[..., 2:]])

    def use(self, lighting: Lighting, wind: bool = False, unit: int = FACING_UNIT) -> None:
        """Bind the table of the grass type's patch and this light; `wind`: with the bend
        coefficients, which still air does not read (they cost twice the rest)."""
        patch = self._patch()
        canopy = self._canopy() if self._canopy is not None else None
        light = (*lighting.sun_direction, lighting.translucency)
        if patch is not None:
            used = self._used
            same = used is not None and used[0] is patch and used[1] == light and used[2] is canopy
            if not same or (wind and not used[3]):
                self.texture.write(np.ascontiguousarray(self.table(lighting, wind)).tobytes())
                self._used = (patch, light, canopy, wind)
        self.texture.use(unit)

    def release(self) -> None:
        self.texture.release()


class SlopeTable:
    """The slope-ratio tables of one grass type (core/facing.py slope_tables), by view direction,
    elevation over the ground and the ground's rise across the view: upright blades on sloping
    ground against the sheared slices (red: the volume multiplies its diffuse factor by it) and
    against upright blades on flat ground (green: the image-based grass, lit by the flat
    ground's facing table); one 3D float texture (shaders/_lighting.glsl slope_ratios), ones
    until the grass type has slices (its canopy), rebuilt when the patch, the canopy or the
    light changes (kept_slope_tables). (The volume's ratio on
    the image-based grass made the meadow's far field worse: README.)"""

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
        ones = np.ones((ACROSS, SLOPES, ELEVATIONS, AZIMUTHS, 2), np.float32)
        self.texture.write(ones.tobytes())
        self._used: tuple | None = None  # the patch, canopy and light the table is of

    def use(self, lighting: Lighting, unit: int = SLOPE_UNIT) -> None:
        patch, canopy = self._patch(), self._canopy()
        light = (*lighting.sun_direction, lighting.translucency)
        if patch is not None and canopy is not None:
            old = self._used
            if old is None or old[0] is not patch or old[1] is not canopy or old[2] != light:
                table = kept_slope_tables(patch, canopy, lighting)
                self.texture.write(np.ascontiguousarray(table).tobytes())
                self._used = (patch, canopy, light)
        self.texture.use(unit)

    def release(self) -> None:
        self.texture.release()


def bind_slopes(program: moderngl.Program, table: SlopeTable | None, lighting: Lighting) -> None:
    """Point a far representation's program at its grass type's slope tables (or tell it there
    are none). The sampler keeps its own unit even without a table: two sampler types on one
    unit are an invalid operation."""
    program["u_slope_ratio"].value = SLOPE_UNIT
    program["u_slopes"].value = table is not None
    if table is not None:
        table.use(lighting)
