import pytest

from core.params import PRESETS, ParameterError, PatchParams


def test_defaults_and_presets_are_valid():
    assert PatchParams().blade_count > 0
    assert set(PRESETS) == {
        "medium long grass",
        "short-cut turf",
        "long thin meadow grass",
        "utility lawn",
    }
    lengths = {name: p.length_max for name, p in PRESETS.items()}
    assert lengths["short-cut turf"] < lengths["utility lawn"] < lengths["long thin meadow grass"]


@pytest.mark.parametrize(
    ("field", "value", "words"),
    [
        ("blade_count", 0, ["blade_count", "1", "100000"]),
        ("bending", 1.5, ["bending", "0.95"]),
        ("tilt_max", -3.0, ["tilt_max", "0", "85"]),
        ("subdivisions", 2.5, ["subdivisions", "whole number"]),
        ("cluster_sigma", "a lot", ["cluster_sigma", "number"]),
    ],
)
def test_out_of_range_is_refused_naming_parameter_and_range(field, value, words):
    with pytest.raises(ParameterError) as info:
        PatchParams().replace(**{field: value})
    for word in words:
        assert word in str(info.value)


def test_min_above_max_is_refused():
    with pytest.raises(ParameterError, match="length_min"):
        PatchParams(length_min=0.5, length_max=0.2)


def test_blades_longer_than_the_patch_is_tall_are_refused_with_the_rule():
    with pytest.raises(ParameterError) as info:
        PatchParams(length_min=0.25, length_max=0.9, patch_height=0.7)
    assert "length_max (0.9) must not exceed patch_height (0.7)" in str(info.value)
    assert PatchParams(length_min=0.25, length_max=0.9, patch_height=0.9).length_max == 0.9


def test_bad_colour_and_unknown_name():
    with pytest.raises(ParameterError, match="tip_color"):
        PatchParams(tip_color=(0.2, 1.4, 0.1))
    with pytest.raises(ParameterError, match="blade_cuont"):
        PatchParams().replace(blade_cuont=3)


def test_round_trip_through_dict():
    p = PRESETS["utility lawn"]
    assert PatchParams.from_dict(p.to_dict()) == p


def test_slice_params_keep_the_mip_chain_possible():
    from core.params import ParameterError, SliceParams

    assert SliceParams().slices == 8
    assert SliceParams(slices=16, width=512, height=128, top=1024).top == 1024
    with pytest.raises(ParameterError, match="slices = 0"):
        SliceParams(slices=0)
    with pytest.raises(ParameterError, match="slice width = 200 must be a power of two"):
        SliceParams(width=200)
    with pytest.raises(ParameterError, match="top slice size = 4096"):
        SliceParams(top=4096)
