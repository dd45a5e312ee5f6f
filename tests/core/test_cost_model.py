"""The cost model of `sward tune --workers`: a frame's time from what the query drew."""

import numpy as np
import pytest

from core.cost_model import CostModel


def _counts(tri, vol, img):
    return {"triangles": tri, "volume_slices": vol, "c_i": img}


def test_the_model_recovers_the_cost_of_each_kind_of_work():
    rng = np.random.default_rng(1)
    counts = [
        _counts(
            int(rng.integers(1e5, 2e6)), int(rng.integers(100, 5000)), int(rng.integers(0, 900))
        )
        for _ in range(12)
    ]
    # 20 ms per million triangles, 5 ms per thousand volume slices, 1 ms per 100 quads, 8 ms
    times = [
        2e-5 * c["triangles"] + 5e-3 * c["volume_slices"] + 1e-2 * c["c_i"] + 8 for c in counts
    ]
    model = CostModel.fit(counts, times)
    assert model.coefficients == pytest.approx((2e-5, 5e-3, 1e-2, 8.0), rel=1e-6)
    assert model.loo_error < 1e-9
    assert model.predict(_counts(1_000_000, 0, 0)) == pytest.approx(28.0)


def test_a_term_that_would_fit_negative_is_dropped_and_noise_shows_in_the_error():
    rng = np.random.default_rng(2)
    counts = [_counts(int(t), int(v), 50) for t, v in rng.integers(1e5, 2e6, (10, 2))]
    # the volume count runs against the time by chance: no work takes negative time
    times = [3e-5 * c["triangles"] - 2e-6 * c["volume_slices"] + 4 for c in counts]
    model = CostModel.fit(counts, times)
    assert min(model.coefficients) >= 0 and model.coefficients[1] == 0
    assert model.coefficients[2] == 0  # the image count never varied: nothing to learn
    honest = [3e-5 * c["triangles"] + 4 for c in counts]
    noisy = [t * (1 + 0.05 * rng.standard_normal()) for t in honest]
    assert 0.005 < CostModel.fit(counts, noisy).loo_error < 0.2
    assert model.to_dict()["terms"] == ["triangles", "volume_slices", "c_i", "constant"]


def test_one_frame_is_not_a_model():
    with pytest.raises(ValueError, match="at least two"):
        CostModel.fit([_counts(1, 1, 1)], [3.0])
