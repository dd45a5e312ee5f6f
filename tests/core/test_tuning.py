"""The knobs of `sward tune` turn the levels as they say, and the front and the choice follow
cost and quality."""

import pytest

from core.lod import LodConfig, LodLevel
from core.tuning import (
    SHIPPED,
    Candidate,
    Knobs,
    as_good_as_shipped,
    at_least_as_good,
    choose,
    first_candidates,
    front,
    neighbours,
    proposals,
    tuned,
)

MEADOW = LodConfig(
    (
        LodLevel("geometry", 0.0, 7.0),
        LodLevel("volume", 5.0, 22.0, slices=8, macro=4),
        LodLevel("image", 18.0, None, macro=16),
    )
)


def test_the_shipped_knobs_leave_the_levels_as_they_are():
    assert tuned(MEADOW, SHIPPED) is MEADOW


def test_near_moves_the_first_hand_over_and_keeps_its_width():
    moved = tuned(MEADOW, Knobs(near=1.5))
    geometry, volume, image = moved.levels
    assert (volume.begin + geometry.end) / 2 == pytest.approx(9.0)  # its centre 6 × 1.5
    assert geometry.end - volume.begin == pytest.approx(2.0)
    assert (image.begin, volume.end) == (18.0, 22.0)  # the far hand-over stays


def test_far_transition_slices_and_macro():
    moved = tuned(MEADOW, Knobs(far=0.75, transition=2.0, slices=-1, macro=1))
    geometry, volume, image = moved.levels
    assert (image.begin + volume.end) / 2 == pytest.approx(15.0)
    assert volume.end - image.begin == pytest.approx(8.0)
    assert geometry.end - volume.begin == pytest.approx(4.0)
    assert volume.slices == 4 and volume.macro == 8 and image.macro == 32
    assert geometry.macro == 1  # geometry draws no macro-cells


def test_knobs_that_break_the_order_of_the_zones_make_no_setting():
    assert tuned(MEADOW, Knobs(near=4.0)) is None  # the first hand-over past the second


def test_neighbours_step_each_knob_both_ways():
    found = neighbours(SHIPPED)
    assert Knobs(near=1.25) in found and Knobs(near=0.8) in found
    assert Knobs(slices=1) in found and Knobs(slices=-1) in found
    assert len(found) == 10 and first_candidates()[0] == SHIPPED


def c(knobs, cost, flip, regions=None, pops=None):
    return Candidate(knobs, cost, flip, regions or {}, pops)


def test_the_front_and_the_choice():
    shipped = c(SHIPPED, 100.0, 0.070, {"geometry": 0.05, "volume": 0.09})
    cheaper_as_good = c(Knobs(slices=-1), 90.0, 0.069, {"geometry": 0.05, "volume": 0.088})
    cheaper_worse_region = c(Knobs(near=0.8), 80.0, 0.068, {"geometry": 0.05, "volume": 0.10})
    dearer_better = c(Knobs(near=1.25), 130.0, 0.060, {"geometry": 0.05, "volume": 0.08})
    all_ = [shipped, cheaper_as_good, cheaper_worse_region, dearer_better]
    assert front(all_) == [cheaper_worse_region, dearer_better]
    assert choose(all_, budget_ms=100.0) is cheaper_worse_region  # the best frame FLIP within
    assert choose(all_, budget_ms=50.0) is None
    assert choose(all_, quality=0.069) is cheaper_worse_region  # the cheapest that reaches it
    # as good in the frame and every region, and cheaper: only the one with fewer slices
    assert as_good_as_shipped(all_, shipped, 100.0) == [cheaper_as_good]
    assert not at_least_as_good(cheaper_worse_region, shipped)
    # popping: no more than the other's or the limit (1.2), whichever is more
    assert not at_least_as_good(c(SHIPPED, 1, 0.07, {}, 1.3), c(SHIPPED, 1, 0.07, {}, 1.1))
    assert at_least_as_good(c(SHIPPED, 1, 0.07, {}, 0.9), c(SHIPPED, 1, 0.07, {}, 0.8))


def test_proposals_are_unseen_neighbours_nearest_the_choice_first():
    a = c(SHIPPED, 100.0, 0.07)
    b = c(Knobs(near=0.8), 80.0, 0.08)
    seen = {a.knobs, b.knobs}
    found = proposals([a, b], seen, b)
    assert not set(found) & seen
    assert found[0] in neighbours(b.knobs)


def test_a_choice_pops_no_more_than_the_shipped_setting_or_the_limit():
    from core.tuning import POPPING_LIMIT, popping_limit

    shipped = c(SHIPPED, 100.0, 0.07, {}, 0.9)
    narrow = c(Knobs(transition=0.2), 90.0, 0.03, {}, 1.6)  # sharp in a still frame, pops
    wide = c(Knobs(near=0.8), 80.0, 0.06, {}, 1.0)
    limit = popping_limit(shipped)
    assert limit == POPPING_LIMIT
    assert choose([shipped, narrow, wide], budget_ms=100.0, popping_limit=limit) is wide
    assert choose([shipped, narrow, wide], budget_ms=100.0) is narrow
    assert popping_limit(c(SHIPPED, 1.0, 0.1, {}, 1.5)) == 1.5
