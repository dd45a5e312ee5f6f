"""Grass types from a terrain colour map (Papavasiliou §3.3, eq. 16): each region goes to the
type whose reference colour it is nearest, borders mix, the soil's region stays bare."""

import colorsys

import numpy as np
import pytest
from scipy.ndimage import gaussian_filter

from core.species import SpeciesRule, patch_reference, rgb_to_hsv, species_densities

GREEN, YELLOW, BROWN = (0.25, 0.55, 0.15), (0.80, 0.72, 0.30), (0.30, 0.25, 0.17)


def _rule(rgb) -> SpeciesRule:
    return SpeciesRule(tuple(colorsys.rgb_to_hsv(*rgb)))


def _image() -> np.ndarray:
    """Three bands, green | yellow | brown, 60 texels each, their borders blurred over a few
    texels, with some noise as a painted map has."""
    image = np.zeros((40, 180, 3))
    image[:, :60], image[:, 60:120], image[:, 120:] = GREEN, YELLOW, BROWN
    image = gaussian_filter(image, (0, 3, 0))
    image += np.random.default_rng(1).normal(0, 0.02, image.shape)
    return np.clip(image, 0, 1)


def test_each_region_goes_to_its_type_borders_mix_and_the_soil_stays_bare():
    density = species_densities(_image(), [_rule(GREEN), _rule(YELLOW)], _rule(BROWN))
    green, yellow = density[..., 0], density[..., 1]
    inside = (
        (slice(None), slice(10, 50)),
        (slice(None), slice(70, 110)),
        (slice(None), slice(130, 170)),
    )
    for region, mine in ((inside[0], green), (inside[1], yellow)):
        assert mine[region].sum() >= 0.9 * density[region].sum()
        assert density[region].sum(axis=-1).mean() > 0.9  # grown, not thinned
    # none on the soil: the paper's draw between the two best kinds gives a noisy texel,
    # where the yellow comes second, a share; the region as a whole stays bare
    soil = density[inside[2]].sum(axis=-1)
    assert soil.mean() < 0.01 and np.percentile(soil, 99) < 0.1
    border = density[:, 58:62]
    assert (border[..., 0] > 0.1).any() and (border[..., 1] > 0.1).any()  # mixed
    assert (density.sum(axis=-1) <= 1.0 + 1e-6).all()


def test_hue_is_measured_round_its_circle():
    reds = np.array([[[1.0, 0.0, 0.02], [1.0, 0.02, 0.0]]])  # hues just below 1 and above 0
    density = species_densities(
        reds, [_rule((1.0, 0.0, 0.0)), _rule((0.0, 1.0, 0.0))], _rule((0.0, 0.0, 1.0))
    )
    assert (density[..., 0] > 0.99).all()


def test_a_types_reference_is_its_blades_mean_colour():
    colours = np.array([[0.2, 0.5, 0.1], [0.4, 0.7, 0.3]])
    h, s, v = patch_reference(colours)
    assert (h, s, v) == pytest.approx(colorsys.rgb_to_hsv(0.3, 0.6, 0.2))
    assert rgb_to_hsv(np.array([0.3, 0.6, 0.2])) == pytest.approx([h, s, v])


@pytest.mark.parametrize(
    "kwargs,words",
    [({"reference": (1.2, 0, 0)}, "0 … 1"), ({"reference": (0, 0, 0), "weights": (0, 0, 0)}, "not all 0"),
     ({"reference": (0, 0, 0), "exponent": 0.0}, "exponent")],
)  # fmt: skip
def test_a_rule_out_of_range_is_refused(kwargs, words):
    with pytest.raises(ValueError, match=words):
        SpeciesRule(**kwargs)
