"""How upright blades on sloping ground light against the slices sheared with it: the slope-ratio
tables the far representations multiply their light by (shaders/_lighting.glsl slope_ratios),
from sums over the patch's blades that any light turns into a table (core/light_moments.py).
core/facing.py holds the table of the blades on flat ground these ratios scale."""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from core.canopy import Canopy
from core.facing import AZIMUTHS, ELEVATIONS, directions
from core.light_moments import LightMoments, powers

# -- upright blades on sloping ground ---------------------------------------------------------
# A blade stands upright wherever it grows (thesis eq. 6.13: the whole blade rises by its
# root's ground), so on a slope the parts of it that lean downhill stand higher over the ground
# beneath them, and those that lean uphill lower, some under it. The slices instead are
# sheared by the ground under each sample (eqs. 6.16–6.18): every part keeps its height over
# the ground below it, as if the blades lay on the slope. Seen along a slope that rises away
# from the eye, the upright blades show their downhill parts, whose eye-facing sides turn down
# and away from the light: the upright blades are darker there than the sheared slices, and
# slope_moments models each (tests/render/test_far_field.py checks the volume against them).
SLOPES = 9  # ratio-table layers: the view's elevation over the ground minus over the horizon
SLOPE_SPAN = np.radians(30.0)  # the outer layers' difference; layer t in -1 … 1 is SPAN · t|t|
RATIO_LIMITS = (0.5, 2.0)  # where a view grazes the ground a few blade tips decide the ratio
GRAZING = np.radians(1.0)  # the least elevation over the ground a view is counted at
MAX_RISE = 1.0  # ground steeper than 45° along the view counts as 45°
# The ground may also rise across the view (a hillside seen obliquely): the upright blades' parts
# that lean across it then stand higher or lower over the ground beside them, and which of them
# show depends on it too: the tables take the rise across the view as well as along it.
ACROSS = 7  # ratio-table blocks: the ground's rise across the view, per unit of run
ACROSS_SPAN = 0.6  # the outer blocks' rise; block t in -1 … 1 is SPAN · t|t| (to the right: +)


def slope_offsets(count: int = SLOPES) -> np.ndarray:
    """The table layers' elevation over the ground minus elevation over the horizon (radians):
    0 (flat ground, ratio 1) is the middle layer, the layers dense about it (shaders invert
    this: shaders/_lighting.glsl)."""
    t = np.linspace(-1.0, 1.0, count)
    return SLOPE_SPAN * t * np.abs(t)


def across_rises(count: int = ACROSS) -> np.ndarray:
    """The table blocks' rise of the ground across the view, to the viewer's right (per unit of
    run): 0 is the middle block, the blocks dense about it (shaders/_lighting.glsl inverts
    this)."""
    t = np.linspace(-1.0, 1.0, count)
    return ACROSS_SPAN * t * np.abs(t)


def slope_moments(
    normals: np.ndarray,
    positions: np.ndarray,
    roots: np.ndarray,
    canopy: Canopy,
    to_eye: np.ndarray,
    theta: np.ndarray,
    sample: int = 3000,
    across: np.ndarray | None = None,
    sheared: bool = True,
) -> tuple[LightMoments, LightMoments | None]:
    """What the blades seen from directions `to_eye` ((m, 3)) at elevations θ over the ground
    ((..., m), radians, several per direction) show of any light, upright and sheared
    (LightMoments of θ's shape; the second None unless `sheared`). Both weigh each vertex by
    |n · e| and by the share of a view at θ that reaches its height (Canopy.transmittance): the
    sheared blade (as the slices are) at its own height y, the upright one at
    y − g · (its offset from the root along the view) − c · (its offset to the viewer's right),
    g = tan θ − tan e the ground's rise per unit run away from the eye, c its rise to the right
    (`across`, θ's shape; 0 if not given), and not at all where that is below the ground."""
    e = np.asarray(to_eye, np.float64).reshape(-1, 3)
    e = e / np.linalg.norm(e, axis=1, keepdims=True)
    shape = np.shape(theta)
    seen = _SeenVertices.of(normals, positions, roots, e, canopy, sample)
    if seen is None:
        none = np.zeros((0, int(np.prod(shape))))
        nothing = LightMoments.of(np.zeros((0, 3)), none, none).reshaped(shape)
        return nothing, nothing if sheared else None
    elevation = np.arcsin(np.clip(e[:, 1], 0.0, 1.0))
    thetas = np.clip(np.asarray(theta, np.float64), GRAZING, 0.5 * np.pi - 1e-3)
    rises = np.zeros(thetas.shape) if across is None else np.broadcast_to(across, thetas.shape)
    upright, sheared_parts = [], []
    for index in np.ndindex(thetas.shape[:-1]):  # a θ for each direction per pass
        t = thetas[index]
        g = np.clip(np.tan(t) - np.tan(elevation), -MAX_RISE, MAX_RISE).astype(np.float32)
        g[np.abs(g) < 1e-9] = 0.0  # flat ground exactly: rounding would move a vertex off its row
        c = np.clip(rises[index], -MAX_RISE, MAX_RISE).astype(np.float32)
        flat = not (g.any() or c.any())
        upright.append(seen.by_rows(t, False) if flat else seen.upright(t, g, c))
        if sheared:
            sheared_parts.append(seen.by_rows(t, True))
    return (
        LightMoments.stack(upright).reshaped(shape),
        LightMoments.stack(sheared_parts).reshaped(shape) if sheared else None,
    )


class _SeenVertices:
    """A sample of a patch's vertices, prepared once for every view of slope_moments: their
    heights, their offsets from the root along and across each view, |n · e|, and the
    patch's side of the light's sums (core/light_moments.py): Σ w |n · e| n^α and
    Σ w |n · e| are one product of the weights times |n · e| with `basis`; the signed sum
    Σ w |n · e| s n = Σ w (n · e) n = (Σ w n nᵀ) e needs no second (k, m) product."""

    @classmethod
    def of(cls, normals, positions, roots, e, canopy: Canopy, sample: int):
        n = np.asarray(normals, np.float64).reshape(-1, 3)
        length = np.linalg.norm(n, axis=1)
        pick = np.flatnonzero(length > 1e-6)
        pick = pick[np.linspace(0, len(pick) - 1, min(len(pick), sample)).astype(np.int64)]
        if len(pick) == 0:
            return None
        position = np.asarray(positions, np.float64).reshape(-1, 3)[pick]
        offset = position[:, [0, 2]] - np.asarray(roots, np.float64).reshape(-1, 2)[pick]
        return cls(n[pick] / length[pick, None], position[:, 1:2], offset, e, canopy)

    def __init__(self, n, y, offset, e, canopy: Canopy) -> None:
        self.e, self.canopy = e, canopy
        ne = n @ e.T  # (k, m)
        away = -e[:, [0, 2]]
        away /= np.maximum(np.linalg.norm(away, axis=1, keepdims=True), 1e-9)  # (m, 2)
        right = np.stack([-away[:, 1], away[:, 0]], axis=1)  # (x, z) to the viewer's right
        # the (k, m) weights in single precision, made by one compiled loop per pass (_seen)
        # rather than as several (k, m) numpy temporaries
        self.along = (offset @ away.T).astype(np.float32)  # each vertex's offset from its root …
        self.sideways = (offset @ right.T).astype(np.float32)  # … along the view and to its right
        self.height = y[:, 0].astype(np.float32)
        self.face = np.abs(ne).astype(np.float32)
        self.basis = np.hstack([powers(n), np.ones((len(n), 1))]).astype(np.float32)  # (k, P + 1)
        self.outer = (n[:, :, None] * n[:, None, :]).reshape(-1, 9).astype(np.float32)  # (k, 9)
        self.seen = np.empty(self.face.shape, np.float32)
        self.weights = np.empty(self.face.shape, np.float32)
        # The sheared blades stand at their own heights y, so each vertex keeps one canopy row
        # in every view (_seen's row of y): their sums are, per row, the sums over its vertices
        # (once) weighted by what reaches that row from each view, not a pass over the vertices
        # a view. So are the upright blades' on flat ground (no rise along or across: y again),
        # which leave out what lies below the ground (the last bin) and equal the sheared
        # exactly.
        rows = canopy.rows
        per_row = np.float32(1.0 / canopy.dy)
        row_of = np.minimum((self.height * per_row).astype(np.int64), rows - 1)  # truncates
        row_of[self.height >= np.float32(canopy.height)] = rows  # above the grass: the last row
        row_of[self.height < 0.0] = rows + 1
        by_row = [np.flatnonzero(row_of == r) for r in range(rows + 2)]
        self.row_sums = np.stack(
            [(self.face[i].T @ self.basis[i]).astype(np.float64) for i in by_row]
        )
        self.row_outer = np.stack([self.outer[i].astype(np.float64).sum(axis=0) for i in by_row])

    def upright(self, t: np.ndarray, g: np.ndarray, c: np.ndarray) -> LightMoments:
        """The sums over the upright vertices seen at elevations t, the ground rising g along
        the view and c across it: weights w (Canopy.transmittance at the vertex's height over
        the ground, none below it), times |n · e|."""
        canopy = self.canopy
        through = np.exp(-canopy.cumulative(t)).astype(np.float32)  # once per depth, direction
        through[through < 1e-30] = 0.0  # no subnormals into the products below
        _seen(self.height, self.along, self.sideways, self.face, g, c, through, canopy.dy,
              canopy.height, self.seen, self.weights)  # fmt: skip
        sums = (self.seen.T @ self.basis).astype(np.float64)
        second = (self.weights.T @ self.outer).astype(np.float64).reshape(-1, 3, 3)  # Σ w n nᵀ
        return LightMoments(sums[:, :-1], np.einsum("mij,mj->mi", second, self.e), sums[:, -1])

    def by_rows(self, t: np.ndarray, below: bool) -> LightMoments:
        """The sums at elevations t with each vertex at its own height (`below`: those under
        the ground count in the first row, as the sheared blades do)."""
        through = np.exp(-self.canopy.cumulative(t)).astype(np.float32).astype(np.float64)
        through[through < 1e-30] = 0.0
        through = np.concatenate([through, through[:1] if below else 0.0 * through[:1]])
        sums = np.einsum("rm,rmp->mp", through, self.row_sums)
        second = np.einsum("rm,rj->mj", through, self.row_outer).reshape(-1, 3, 3)
        return LightMoments(sums[:, :-1], np.einsum("mij,mj->mi", second, self.e), sums[:, -1])


@numba.njit(cache=True)
def _seen(height, along, sideways, face, g, c, through, dy, top, seen, weights):
    """Per vertex k and direction m: its height over the ground upright, y − g_m along −
    c_m sideways, the share of the view that reaches it (`through`: exp(−cumulative) by row,
    Canopy.row_index's rows, the last above the grass; none below the ground), and that times
    |n · e|."""
    rows = through.shape[0] - 1
    per_row = np.float32(1.0 / dy)
    top = np.float32(top)
    for k in range(height.shape[0]):
        for m in range(g.shape[0]):
            h = height[k] - g[m] * along[k, m] - c[m] * sideways[k, m]
            if h < 0.0:
                w = np.float32(0.0)
            elif h >= top:
                w = through[rows, m]
            else:
                w = through[min(int(h * per_row), rows - 1), m]
            weights[k, m] = w
            seen[k, m] = w * face[k, m]


@dataclass(frozen=True)
class SlopeMoments:
    """slope_tables' sums for any light: the upright blades' (blocks, slopes, m) and the
    sheared ones' (slopes, m), m the table's directions."""

    upright: LightMoments
    sheared: LightMoments
    elevations: int
    azimuths: int


def slope_moments_table(
    normals: np.ndarray,
    positions: np.ndarray,
    roots: np.ndarray,
    canopy: Canopy,
    azimuths: int = AZIMUTHS,
    elevations: int = ELEVATIONS,
    slopes: int = SLOPES,
    sample: int = 3000,
    blocks: int = ACROSS,
) -> SlopeMoments:
    """What slope_tables needs of the patch, once for every light (the table's directions,
    each at the elevations over the ground of slope_offsets, the rises of across_rises)."""
    e = directions(azimuths, elevations).reshape(-1, 3)
    theta = np.arcsin(e[:, 1])[None, :] + slope_offsets(slopes)[:, None]  # (slopes, m)
    rises = across_rises(blocks)
    middle = blocks // 2  # no rise across the view
    level, sheared = slope_moments(normals, positions, roots, canopy, e, theta, sample)
    others = [b for b in range(blocks) if b != middle]
    shape = (len(others), *theta.shape)
    tilted, _ = slope_moments(
        normals, positions, roots, canopy, e, np.broadcast_to(theta, shape), sample,
        across=np.broadcast_to(rises[others][:, None, None], shape), sheared=False,
    )  # fmt: skip
    tilted_parts = iter(
        LightMoments(tilted.powers[i], tilted.signed[i], tilted.total[i])
        for i in range(len(others))
    )
    parts = [level if b == middle else next(tilted_parts) for b in range(blocks)]
    assert sheared is not None
    return SlopeMoments(LightMoments.stack(parts), sheared, elevations, azimuths)


def slope_ratios(moments: SlopeMoments, light_dir: np.ndarray, translucency: float) -> np.ndarray:
    """slope_tables of the patch the moments are of, under this light."""
    upright = moments.upright.lit(light_dir, translucency)  # (blocks, slopes, m)
    sheared = moments.sheared.lit(light_dir, translucency)  # (slopes, m)
    blocks, slopes = upright.shape[:2]
    flat = upright[blocks // 2, slopes // 2]  # elevation over the ground = the direction's
    out = np.stack(
        [
            np.where(sheared > 0.0, upright / np.maximum(sheared, 1e-6), 1.0),
            np.where(flat > 0.0, upright / np.maximum(flat, 1e-6), 1.0),
        ],
        axis=-1,
    )
    out = np.clip(out, *RATIO_LIMITS)
    return out.reshape(blocks, slopes, moments.elevations, moments.azimuths, 2).astype(np.float32)


def slope_tables(
    normals: np.ndarray,
    positions: np.ndarray,
    roots: np.ndarray,
    canopy: Canopy,
    light_dir: np.ndarray,
    translucency: float,
    azimuths: int = AZIMUTHS,
    elevations: int = ELEVATIONS,
    slopes: int = SLOPES,
    sample: int = 3000,
    blocks: int = ACROSS,
) -> np.ndarray:
    """(blocks, slopes, elevations, azimuths, 2) float32 at the table's directions, each layer
    at elevation over the ground = the direction's + the layer's offset (slope_offsets), each
    block with the ground rising across the view by its rise (across_rises):
    [..., 0] upright blades over sheared ones (the volume's slices, sheared with the ground),
    [..., 1] upright blades on the slope over upright blades on flat ground seen from the same
    direction (the image-based grass, lit by the flat ground's facing table); 1 on flat ground."""
    moments = slope_moments_table(
        normals, positions, roots, canopy, azimuths, elevations, slopes, sample, blocks
    )
    return slope_ratios(moments, light_dir, translucency)
