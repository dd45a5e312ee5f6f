"""Per-blade density thresholds on (0, 1] (thesis 3.3 and 4.1.3).

A blade is drawn where the local density is at least its threshold. Two distributions:
uniform (eq. 4.3) and clustered (eqs. 4.4-4.6): a truncated Gaussian around the histogram-
equalised low-frequency Perlin noise at the blade root.
"""

from __future__ import annotations

import numpy as np

from core.noise import equalized_noise_map

NOISE_RESOLUTION = 256
NOISE_PERIOD = 4


def uniform_thresholds(count: int, rng: np.random.Generator) -> np.ndarray:
    """Thresholds drawn uniformly from (0, 1]."""
    return (1.0 - rng.random(count)).astype(np.float32)


def truncated_gaussian(mu: np.ndarray, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """Samples of N(mu, sigma) truncated to (0, 1], by inverse transform (eq. 4.6)."""
    mu = np.asarray(mu, dtype=np.float64)
    if sigma <= 0.0:
        return np.clip(mu, np.nextafter(0.0, 1.0), 1.0)
    from math import erf, sqrt

    verf = np.vectorize(erf, otypes=[np.float64])

    def cdf(z: np.ndarray) -> np.ndarray:
        return 0.5 * (1.0 + verf(z / sqrt(2.0)))

    lo = cdf((0.0 - mu) / sigma)
    hi = cdf((1.0 - mu) / sigma)
    u = lo + rng.random(mu.shape) * (hi - lo)
    x = mu + sigma * _norm_ppf(u)
    return np.clip(x, np.nextafter(0.0, 1.0), 1.0)


def _norm_ppf(p: np.ndarray) -> np.ndarray:
    """Inverse standard normal CDF (Acklam's rational approximation, |error| < 1.2e-9)."""
    p = np.clip(np.asarray(p, dtype=np.float64), 1e-300, 1 - 1e-16)
    a = (
        -3.969683028665376e01,
        2.209460984245205e02,
        -2.759285104469687e02,
        1.383577518672690e02,
        -3.066479806614716e01,
        2.506628277459239e00,
    )
    b = (
        -5.447609879822406e01,
        1.615858368580409e02,
        -1.556989798598866e02,
        6.680131188771972e01,
        -1.328068155288572e01,
    )
    c = (
        -7.784894002430293e-03,
        -3.223964580411365e-01,
        -2.400758277161838e00,
        -2.549732539343734e00,
        4.374664141464968e00,
        2.938163982698783e00,
    )
    d = (7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e00, 3.754408661907416e00)
    out = np.empty_like(p)
    low = p < 0.02425
    high = p > 1 - 0.02425
    mid = ~(low | high)
    q = np.sqrt(-2 * np.log(p[low]))
    out[low] = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / (
        (((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1
    )
    q = np.sqrt(-2 * np.log(1 - p[high]))
    out[high] = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / (
        (((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1
    )
    q = p[mid] - 0.5
    r = q * q
    out[mid] = (
        (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5])
        * q
        / (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1)
    )
    return out


def clustered_thresholds(
    roots: np.ndarray, sigma: float, rng: np.random.Generator, seed: int
) -> np.ndarray:
    """Clustered thresholds for blades rooted at `roots` (n, 2) in the unit square.

    mu = equalised noise at the root (eq. 4.5); threshold ~ N(mu, sigma) on (0, 1] (eq. 4.6).
    Truncating the Gaussian at the ends of the interval thins the marginal near 0 and 1, which
    would break the linear relation between density and visible blades that the thesis asks
    for; a final rank transform restores an exactly uniform marginal without changing which
    blades appear first, so the clusters stay.
    """
    noise = equalized_noise_map(NOISE_RESOLUTION, NOISE_PERIOD, seed)
    idx = np.clip((roots * NOISE_RESOLUTION).astype(np.int64), 0, NOISE_RESOLUTION - 1)
    mu = noise[idx[:, 0], idx[:, 1]]
    raw = truncated_gaussian(mu, sigma, rng)
    return rank_to_uniform(raw, rng)


def rank_to_uniform(values: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Replace values by their jittered ranks on (0, 1]; order kept, marginal uniform."""
    n = values.size
    order = np.argsort(values, kind="stable")
    ranks = np.empty(n, dtype=np.float64)
    ranks[order] = np.arange(n)
    return ((ranks + 1.0 - rng.random(n)) / n).astype(np.float32)
