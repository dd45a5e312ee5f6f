"""What a view at a low elevation meets of a grass patch (issue: the LOD image matches
all-geometry). The image-based grass is one slice seen from above; far away it is seen nearly
level, where the blades hide one another's lower parts, and how deep a view reaches depends on
its elevation and on how densely the blades stand at each height.

From the vertical slices (rows run upward, row 0 at the ground), per row y of the patch:
- the share of a level ray stopped crossing one patch, α(y) = 1 − Π_k (1 − ā_k(y)) over the
  slices k of a family (ā: a slice's mean alpha along the row), so the extinction per patch
  length is σ(y) = −ln(1 − α(y));
- the blades' colour there, c(y), alpha-weighted over the slices.
A ray that enters the grass from above at elevation θ descends Δy while it travels Δy / tan θ,
so the share it gives row y is w(y) = T(y) · (1 − exp(−σ(y) Δy / tan θ)), T the transmittance
of the rows above. The table holds, per elevation, Σ w c / Σ w: the colour met; and the same
mean of AO_blade's height term (shade_met), and the share of a view that reaches a height
(transmittance), which weighs the blades' diffuse factor (core/facing.py). A slice's mean alpha
along a row says less than the blades stop there: σ counts GAIN times."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# A ray meets this many times the blades that the slices' mean alpha says: the volume's
# CROSSING_GAIN (shaders/volume.glsl), measured there against the blades. Here 1.5 gave the
# best sward quality figures (of 1.0, 1.5, 2.0 over the README cameras: sums of the 11 frame
# figures 23.2, 22.6, 22.8; the DEM alone prefers 1.0, the flat scenes 2.0); since the slope
# tables take the ground's rise across the view, 1.75 does (1.5, 1.75, 2.0: 20.54, 20.43,
# 20.55; the image-based regions at 480 × 270 gain most, the DEM's at 1024 × 768 lose).
GAIN = 1.75
ELEVATIONS = 8  # table entries: θ_j = 90° · ((j + 0.5) / 8)², dense near the horizon


def elevations(count: int = ELEVATIONS) -> np.ndarray:
    """The table's elevations in radians (the shaders invert this: shaders/image.glsl)."""
    return 0.5 * np.pi * ((np.arange(count) + 0.5) / count) ** 2


def _profile(color: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Of one family of vertical slices ((n, rows, w, 4), rows running upward): the extinction
    per patch length σ(y) and the alpha-weighted colour c(y) of each row."""
    a = color[..., 3]
    alpha = np.clip(a.mean(axis=2), 0.0, 1.0)  # (n, rows)
    through = 1.0 - np.prod(1.0 - alpha, axis=0)  # (rows,)
    sigma = -np.log(np.maximum(1.0 - through, 1e-6))  # per patch length
    n, rows, w = a.shape
    # per row, the colour weighted by alpha (one batched product over the columns)
    sums = np.matmul(a.reshape(n * rows, 1, w), color[..., :3].reshape(n * rows, w, 3))
    c = sums.reshape(n, rows, 3).sum(axis=0) / np.maximum(a.sum(axis=(0, 2)), 1e-9)[:, None]
    return sigma, c


def _met(sigma, c, dy: float, theta: float, other=None) -> tuple[float, np.ndarray]:
    """A ray entering the rows (σ, c per row, running upward) from above at elevation θ: the
    share of it their blades stop, and the colour they show it. `other`: the extinction per
    row of another type's blades standing among them, which stop the ray too and take their
    own share of it."""
    run = GAIN * dy / max(np.tan(theta), 1e-3)  # the patch lengths a row's height takes
    t_own = sigma[::-1] * run  # the rows from the top down
    t_all = t_own if other is None else t_own + other[::-1] * run
    stopped = np.exp(-np.concatenate([[0.0], np.cumsum(t_all)[:-1]])) * (1.0 - np.exp(-t_all))
    w = stopped * t_own / np.maximum(t_all, 1e-12)  # of what a row stops, these blades' share
    return float(w.sum()), (w[:, None] * c[::-1]).sum(axis=0) / max(float(w.sum()), 1e-9)


def level_view(families: list[np.ndarray], height: float, count: int = ELEVATIONS) -> np.ndarray:
    """(count, 3) colours met at each table elevation, averaged over the families of vertical
    slices ((n, rows, w, 4) colour + alpha arrays, 0 … 1, rows running upward)."""
    colours = []
    for color in families:
        sigma, c = _profile(color)
        dy = height / color.shape[1]
        colours.append([_met(sigma, c, dy, theta)[1] for theta in elevations(count)])
    return np.mean(colours, axis=0).astype(np.float32)


@dataclass(frozen=True)
class BladeSides:
    """What a level ray meets of a patch's blades, from their triangles: each triangle gives a
    level ray crossing the patch the optical depth of its area seen along the ray, averaged over
    the horizontal directions (2/π |n_xz| of it), times the share of it the blade's texture
    keeps. A slice's mean alpha saturates where a slab's blades overlap (dense turf in few
    slices: a row all but opaque says little of how many blades stand in it), so the depth
    from the side is counted on the blades themselves."""

    heights: np.ndarray  # the triangles' centroid heights, rising
    above: np.ndarray  # the depth of the triangles from each of those up

    @classmethod
    def of(cls, positions: np.ndarray, uv: np.ndarray, triangles: np.ndarray) -> BladeSides:
        """From a patch's vertex positions (m, 3), uv (m, 2) and triangle indices (t, 3)."""
        from core.patch import blade_fill

        p = np.asarray(positions, np.float64)
        a, b, c = p[triangles[:, 0]], p[triangles[:, 1]], p[triangles[:, 2]]
        cross = np.cross(b - a, c - a)  # twice the area along the normal
        seen = 0.5 * np.hypot(cross[:, 0], cross[:, 2]) * (2.0 / np.pi)
        depth = seen * blade_fill(np.asarray(uv)[triangles, 1].mean(axis=1))
        order = np.argsort((a[:, 1] + b[:, 1] + c[:, 1]) / 3.0)
        heights = ((a[:, 1] + b[:, 1] + c[:, 1]) / 3.0)[order]
        return cls(heights, np.cumsum(depth[order][::-1])[::-1])

    def column(self, above: float = 0.0) -> float:
        """The depth of the blades from height `above` up, per patch length of a level ray."""
        i = int(np.searchsorted(self.heights, above))
        return float(self.above[i]) if i < len(self.above) else 0.0


@dataclass(frozen=True)
class Canopy:
    """The rows' extinction and colour of each family of a patch's vertical slices (what the
    tables here are computed from), kept small enough to keep beside the slices' textures."""

    profiles: tuple[tuple[np.ndarray, np.ndarray], ...]  # per family: σ (rows,), c (rows, 3)
    height: float
    sides: BladeSides | None = None  # the blades' own depth from the side, where known

    @classmethod
    def of(
        cls, families: list[np.ndarray], height: float, sides: BladeSides | None = None
    ) -> Canopy:
        return cls(tuple(_profile(color) for color in families), float(height), sides)

    def sigma_at(self, y: np.ndarray) -> np.ndarray:
        """Extinction per patch length at heights y (world units), the families' mean; 0 above
        the grass."""
        sigma = np.mean([profile[0] for profile in self.profiles], axis=0)
        rows = np.floor(np.asarray(y) / self.height * len(sigma)).astype(np.int64)
        inside = (rows >= 0) & (rows < len(sigma))
        return np.where(inside, sigma[np.clip(rows, 0, len(sigma) - 1)], 0.0)

    def transmittance(self, y: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The share of a view from elevation θ (radians, (m,)) that reaches height y (world
        units, (k,)) through the rows above it: (k, m), the families' mean extinction, half of
        y's own row counted."""
        return self.reach(np.asarray(y)[:, None], np.asarray(theta)[None, :])

    def reach(self, y: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The same, element by element of y and θ broadcast together."""
        depths, index = self.depths(y)
        return np.exp(-depths[index] / np.maximum(np.tan(np.asarray(theta)), 1e-3))

    def depths(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """reach's optical depths: the few values there are ((rows + 1,), the last 0: above the
        grass) and each y's index into them (y's shape); reach(y, θ) = exp(−depth / tan θ), so
        a caller with many y per θ takes the exponential once per value and θ."""
        sigma = GAIN * np.mean([profile[0] for profile in self.profiles], axis=0)
        dy = self.height / len(sigma)
        above = np.concatenate([np.cumsum(sigma[::-1])[::-1], [0.0]])  # rows r … top
        values = np.append((above[1:] + 0.5 * sigma) * dy, 0.0)
        y = np.asarray(y)
        rows = np.clip(np.floor(y / dy).astype(np.int64), 0, len(sigma) - 1)
        return values, np.where(y >= self.height, len(sigma), rows)

    def side_column(self, above: float = 0.0) -> float:
        """The optical depth of the grass a level ray meets per patch length, summed over the
        heights from `above` (world units) to the top: Σ σ(y) dy. From the blades themselves
        where known (`sides`), else from the rows of the slices (the families' mean, as their
        mean alpha says it, no GAIN). A ray at elevation θ crosses those heights over 1 / tan θ
        patch lengths for each unit of height, so its depth through them from the side is this
        / tan θ (the image-based grass's coverage, shaders/image.glsl; the volume's floor)."""
        if self.sides is not None:
            return self.sides.column(above)
        sigma = np.mean([profile[0] for profile in self.profiles], axis=0)
        dy = self.height / len(sigma)
        lows = np.arange(len(sigma)) * dy
        part = np.clip((lows + dy - above) / dy, 0.0, 1.0)  # of each row, the share above
        return float((sigma * part).sum() * dy)

    def shade_met(
        self, ao_height: float, under: Canopy | None = None, count: int = ELEVATIONS
    ) -> np.ndarray:
        """Per table elevation, the mean of 1 − smoothstep(0, B_height, y) over the heights y a
        view from there meets of these blades (weighted as the colour is): AO_blade (eq. 6.11)
        of what the view meets is 1 − B_impact · density · this ((count,), the families' mean).
        `under`: another type's blades standing among these (as in `over`), which take the
        rays they stop."""
        shade = []
        for sigma, _c in self.profiles:
            dy = self.height / len(sigma)
            y = (np.arange(len(sigma)) + 0.5) * dy  # rows running upward
            t = np.clip(y / max(ao_height, 1e-6), 0.0, 1.0)
            dark = (1.0 - t * t * (3.0 - 2.0 * t))[:, None]
            other = None if under is None else under.sigma_at(y)
            shade.append([float(_met(sigma, dark, dy, theta, other)[1][0])
                          for theta in elevations(count)])  # fmt: skip
        return np.mean(shade, axis=0).astype(np.float32)

    def over(self, under: Canopy, count: int = ELEVATIONS) -> tuple[np.ndarray, np.ndarray]:
        """Of this grass standing in another type's (`under`, the shorter): per table
        elevation, the share of a ray these blades stop before anything else does, the other
        type's blades standing among them where both reach, and the colour they show it
        ((count,), (count, 3)). What the other type stops, or nothing, the other type's
        slice beneath draws."""
        shares, colours = [], []
        for sigma, c in self.profiles:
            dy = self.height / len(sigma)
            other = under.sigma_at((np.arange(len(sigma)) + 0.5) * dy)  # rows running upward
            met = [_met(sigma, c, dy, theta, other) for theta in elevations(count)]
            shares.append([m[0] for m in met])
            colours.append([m[1] for m in met])
        return (
            np.mean(shares, axis=0).astype(np.float32),
            np.mean(colours, axis=0).astype(np.float32),
        )
