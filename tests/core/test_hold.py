"""Adaptive LOD's controller holds a frame time with one factor, without breathing."""

import itertools

import pytest

from core.hold import BAND, STEP_MAX, HoldFrameTime
from core.lod import LodConfig


def frames(hold: HoldFrameTime, cost, n: int) -> list[float]:
    """Drive the controller with a frame cost that depends on the factor; the factors seen."""
    seen = []
    for _ in range(n):
        hold.update(cost(hold.factor))
        seen.append(hold.factor)
    return seen


@pytest.mark.parametrize("target", [50.0, 200.0])
def test_the_factor_settles_where_the_frame_costs_the_target(target):
    cost = lambda f: 100.0 * f**2 + 10.0  # noqa: E731  (the geometry's area grows as f²)
    hold = HoldFrameTime(target)
    seen = frames(hold, cost, 40)
    assert abs(cost(hold.factor) / target - 1.0) <= BAND + 0.02
    assert all(
        b / a <= STEP_MAX + 1e-9 and a / b <= STEP_MAX + 1e-9 for a, b in itertools.pairwise(seen)
    )


def test_noise_within_the_band_does_not_move_the_zones():
    hold = HoldFrameTime(100.0)
    for ms in (95.0, 104.0, 97.0, 106.0, 99.0, 93.0, 107.0):
        assert not hold.update(ms)
    assert hold.factor == 1.0
    assert not hold.update(300.0)  # one slow frame is not a trend: the median of three
    assert hold.update(300.0)
    assert hold.factor < 1.0


def test_a_bad_target_is_refused():
    with pytest.raises(ValueError, match="above 0"):
        HoldFrameTime(0.0)


def test_scaled_moves_every_zone_and_keeps_the_rest():
    config = LodConfig()
    half = config.scaled(0.5)
    assert [lv.begin for lv in half.levels] == [lv.begin * 0.5 for lv in config.levels]
    assert half.levels[-1].end is None and half.levels[1].slices == config.levels[1].slices
    assert config.scaled(1.0) is config
