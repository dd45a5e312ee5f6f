"""The blades' mean diffuse factor with the light kept apart (core/facing.py's tables).

Every table of core/facing.py is, per entry, Σ_k w_k l(n_k) / Σ_k w_k over the patch's normals
n_k, with weights w_k that depend on the view and the blades (how much of the face a viewer sees,
how much of a view reaches it) but not on the light, which enters through l alone. Seen from e,
the face turned to the viewer is s n, s = sign(n · e), and (shaders/_lighting.glsl)

    l = max(s n·L, 0) + t max(−s n·L, 0) = a |n·L| + b s n·L,   a = (1 + t) / 2, b = (1 − t) / 2.

The second term is linear in L: Σ w s n, three numbers an entry. The first is |x| of x = n·L,
replaced by the polynomial of degree LIGHT_DEGREE closest to it over −1 … 1 (Legendre's
truncation); on unit vectors that is a homogeneous polynomial of the same degree in n, so
Σ w p(n·L) = Σ_α c_α(L) Σ w n^α over the monomials α of that degree. The sums Σ w n^α are the
patch's (LightMoments, once per patch and view table), c(L) the light's: a light change is a
small product, not a pass over the blades. Over the blades of a patch, whose normals turn every
way about the vertical, the tables differ from the exact sums by under 1e-3
(tests/core/test_light_moments.py). Where most normals lie square to the light the polynomial's
error at |x|'s kink shows: blades standing upright (tilt 0, horizontal normals) under a sun
high above them are lit nearly edge-on, and their table is up to 0.004 too bright with the sun
at 75°, 0.033 at the zenith (where the blades' own factor is 0)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

LIGHT_DEGREE = 12  # of |n·L|'s polynomial: 2.5e-4 on the meadow's tables (8: 8e-4)


@lru_cache(maxsize=1)
def _exponents() -> np.ndarray:
    """(P, 3) exponents (a, b, c) of the monomials x^a y^b z^c of degree LIGHT_DEGREE."""
    d = LIGHT_DEGREE
    return np.array([(a, b, d - a - b) for a in range(d + 1) for b in range(d + 1 - a)])


def powers(normals: np.ndarray, dtype: type = np.float64) -> np.ndarray:
    """(k, P) the monomials of degree LIGHT_DEGREE of unit normals (k, 3), in `dtype`."""
    n: np.ndarray = np.asarray(normals, dtype)
    e = _exponents()
    # n^0 … n^d per component by repeated products (cheaper than a float power per entry)
    table: np.ndarray = np.empty((len(n), LIGHT_DEGREE + 1, 3), dtype)  # (k, d + 1, 3)
    table[:, 0] = 1.0
    for j in range(1, LIGHT_DEGREE + 1):
        np.multiply(table[:, j - 1], n, out=table[:, j])
    return table[:, e[:, 0], 0] * table[:, e[:, 1], 1] * table[:, e[:, 2], 2]


@lru_cache(maxsize=1)
def _fit() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """|x|'s polynomial (power-series coefficients), points spread over the sphere and the
    pseudo-inverse that takes a function's values there to its monomials' coefficients (exact
    for the polynomials of degree LIGHT_DEGREE that are even on the sphere)."""
    from numpy.polynomial import legendre

    x = np.cos(np.linspace(0.0, np.pi, 4001))
    series = legendre.leg2poly(legendre.legfit(x, np.abs(x), LIGHT_DEGREE))
    series[1::2] = 0.0  # |x| is even: its odd terms are rounding
    count = 4 * len(_exponents())
    k = np.arange(count) + 0.5
    polar, turn = np.arccos(1.0 - 2.0 * k / count), np.pi * (1.0 + 5.0**0.5) * k
    points = np.stack(
        [np.sin(polar) * np.cos(turn), np.cos(polar), np.sin(polar) * np.sin(turn)], axis=1
    )
    return series, points, np.linalg.pinv(powers(points))


def light_coefficients(light_dir: np.ndarray) -> np.ndarray:
    """(P,) c(L): Σ_α c_α n^α = p(n · L) on unit n, p the polynomial of |x|."""
    series, points, inverse = _fit()
    values = np.polynomial.polynomial.polyval(points @ np.asarray(light_dir, np.float64), series)
    return inverse @ values


@dataclass(frozen=True)
class LightMoments:
    """Per table entry (any shape): Σ w n^α over the monomials α, Σ w s n and Σ w."""

    powers: np.ndarray  # (*shape, P)
    signed: np.ndarray  # (*shape, 3)
    total: np.ndarray  # shape

    @classmethod
    def of(cls, normals: np.ndarray, weights: np.ndarray, facing: np.ndarray) -> LightMoments:
        """From unit normals (k, 3), their weights (k, m) and s = sign(n · e) (k, m): (m,)."""
        w = np.asarray(weights, np.float64)
        n = np.asarray(normals, np.float64)
        return cls(w.T @ powers(n), (w * facing).T @ n, w.sum(axis=0))

    @classmethod
    def stack(cls, parts: list[LightMoments]) -> LightMoments:
        return cls(
            np.stack([p.powers for p in parts]),
            np.stack([p.signed for p in parts]),
            np.stack([p.total for p in parts]),
        )

    def reshaped(self, shape: tuple[int, ...]) -> LightMoments:
        """The same sums with their entries laid out in `shape`."""
        return LightMoments(
            self.powers.reshape(*shape, -1),
            self.signed.reshape(*shape, 3),
            self.total.reshape(shape),
        )

    def lit(self, light_dir: np.ndarray, translucency: float) -> np.ndarray:
        """The mean diffuse factor of each entry under this light (float64, its shape). The
        product keeps the sums' precision: single precision for kept sums
        (render/derived_cache.py), which differs from double by under 1e-6 on the tables and
        spares a double copy of them."""
        light = np.asarray(light_dir, np.float64)
        a, b = 0.5 * (1.0 + translucency), 0.5 * (1.0 - translucency)
        kind = self.powers.dtype
        summed = a * (self.powers @ light_coefficients(light).astype(kind)).astype(np.float64)
        summed += b * (self.signed @ light.astype(kind))
        return np.where(self.total > 0.0, summed / np.maximum(self.total, 1e-12), 0.0)
