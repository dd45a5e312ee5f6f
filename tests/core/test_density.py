import numpy as np
import pytest
from scipy import stats
from scipy.spatial import cKDTree

from core.density import rank_to_uniform, truncated_gaussian
from core.noise import equalized_noise_map, perlin2d
from core.params import PatchParams
from core.patch import generate_patch

N = 5000


def thresholds(clustered: bool, sigma: float = 0.12, seed: int = 3) -> tuple:
    p = generate_patch(
        PatchParams(
            blade_count=N, subdivisions=1, clustered=clustered, cluster_sigma=sigma, seed=seed
        )
    )
    return p.roots, p.thresholds


@pytest.mark.parametrize(
    ("clustered", "sigma"), [(False, 0.0), (True, 0.0), (True, 0.12), (True, 10.0)]
)
def test_thresholds_are_uniform_on_unit_interval(clustered, sigma):
    _, t = thresholds(clustered, sigma)
    assert t.min() > 0.0 and t.max() <= 1.0
    assert stats.kstest(t, "uniform").pvalue > 0.01


def clark_evans(points: np.ndarray) -> float:
    """Mean nearest-neighbour distance over its expectation for a uniform (Poisson) pattern on
    the periodic unit square: 1 for random, < 1 for clumped."""
    tree = cKDTree(points, boxsize=1.0)
    d, _ = tree.query(points, k=2)
    return float(d[:, 1].mean() / (0.5 / np.sqrt(len(points))))


def test_clustered_patch_is_clumped_at_low_density():
    roots_u, t_u = thresholds(False)
    roots_c, t_c = thresholds(True, 0.12)
    roots_s, t_s = thresholds(True, 0.0)
    r_u = clark_evans(roots_u[t_u <= 0.1])
    r_c = clark_evans(roots_c[t_c <= 0.1])
    r_s = clark_evans(roots_s[t_s <= 0.1])
    assert r_u > 0.9
    assert r_c < 0.8 * r_u
    assert r_s < r_c  # sigma 0 clusters hardest


def test_large_sigma_behaves_like_uniform():
    roots, t = thresholds(True, 10.0)
    assert clark_evans(roots[t <= 0.1]) > 0.9


@pytest.mark.parametrize("clustered", [False, True])
def test_visible_blades_linear_in_density(clustered):
    _, t = thresholds(clustered)
    densities = np.linspace(0.05, 1.0, 20)
    visible = np.array([(t <= d).sum() for d in densities])
    assert np.abs(visible - densities * N).max() < 0.02 * N


def test_truncated_gaussian_stays_in_interval_and_centres_on_mu():
    rng = np.random.default_rng(0)
    x = truncated_gaussian(np.full(20000, 0.5), 0.1, rng)
    assert x.min() > 0.0 and x.max() <= 1.0
    assert abs(x.mean() - 0.5) < 0.01 and abs(x.std() - 0.1) < 0.01


def test_rank_to_uniform_keeps_order():
    rng = np.random.default_rng(1)
    v = rng.normal(size=1000)
    u = rank_to_uniform(v, rng)
    assert np.array_equal(np.argsort(v), np.argsort(u))


def test_noise_tiles_and_equalises():
    x = np.linspace(0, 1, 50)
    assert np.allclose(perlin2d(x, np.zeros(50), 4, 7), perlin2d(x, np.ones(50), 4, 7))
    m = equalized_noise_map(64, 4, 7)
    assert stats.kstest(m.ravel(), "uniform").pvalue > 0.5
