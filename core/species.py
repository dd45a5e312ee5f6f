"""Grass types placed from a terrain colour map (Papavasiliou 2015, §3.3, eqs. 16–18): each
grass type, and the bare soil, has a reference colour in HSV, a weight per component and an
exponent; at every texel each scores

    s_i = ‖(r_i − b) ⊙ w‖^(−p)                                          (eq. 16)

against the map's colour b there (hue measured around its circle). The paper grows one plant
per seed, of the best-scoring kind or, with probability s_1 / (s_0 + s_1), of the second best,
and none where the soil wins the draw. A density map holds the expected share instead: the two
best kinds share the texel in proportion to their scores, the others get nothing, and the
soil's share stays bare. Borders between two kinds mix; a kind next to the soil thins out.

The references follow from what the person made unless the person sets one: a grass type's is
the mean colour of its patch's blades, the soil's is the light's soil colour (core/lighting.py).
The weights, exponents and set references are the document's `species` and saved with it."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

TINY = 1e-6  # a distance below this scores as this: the reference colour itself


@dataclass(frozen=True)
class SpeciesRule:
    """How one kind (a grass type or the soil) scores a colour."""

    reference: tuple[float, float, float]  # HSV, each 0 … 1
    # hue, saturation, value alike; a map whose shadows darken the ground wants less value
    weights: tuple[float, float, float] = (1.0, 1.0, 1.0)
    exponent: float = 4.0  # p: larger for sharper borders between kinds

    def __post_init__(self) -> None:
        if not all(0.0 <= c <= 1.0 for c in self.reference):
            raise ValueError(f"species reference {self.reference}: each component 0 … 1")
        if not all(w >= 0.0 for w in self.weights) or not any(self.weights):
            raise ValueError(f"species weights {self.weights}: not negative, not all 0")
        if not 0.1 <= self.exponent <= 32.0:
            raise ValueError(f"species exponent {self.exponent:g} out of range; 0.1 … 32")


def rgb_to_hsv(rgb: np.ndarray) -> np.ndarray:
    """(…, 3) RGB in 0 … 1 as HSV in 0 … 1 (hue in turns)."""
    rgb = np.asarray(rgb, np.float64)
    top, bottom = rgb.max(axis=-1), rgb.min(axis=-1)
    span = top - bottom
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    safe = np.where(span > 0, span, 1.0)
    hue = np.where(
        top == r, (g - b) / safe, np.where(top == g, 2.0 + (b - r) / safe, 4.0 + (r - g) / safe)
    )
    hue = np.where(span > 0, (hue / 6.0) % 1.0, 0.0)
    saturation = np.where(top > 0, span / np.where(top > 0, top, 1.0), 0.0)
    return np.stack([hue, saturation, top], axis=-1)


def scores(hsv: np.ndarray, rules: list[SpeciesRule]) -> np.ndarray:
    """(kinds, …) eq. 16 for each rule at each colour of `hsv` (…, 3)."""
    out = []
    for rule in rules:
        d = hsv - np.asarray(rule.reference)
        d[..., 0] = np.abs(d[..., 0])
        d[..., 0] = np.minimum(d[..., 0], 1.0 - d[..., 0])  # hue goes round
        distance = np.linalg.norm(d * np.asarray(rule.weights), axis=-1)
        out.append(np.maximum(distance, TINY) ** -rule.exponent)
    return np.stack(out)


def species_densities(rgb: np.ndarray, grass: list[SpeciesRule], soil: SpeciesRule) -> np.ndarray:
    """(rows, columns, len(grass)) density per grass type from a colour map (rows, columns,
    3) in 0 … 1: the two best-scoring kinds share each texel by their scores; the soil's share
    is bare."""
    s = scores(rgb_to_hsv(rgb), [*grass, soil])  # the soil last
    order = np.argsort(-s, axis=0)
    first, second = order[0], order[1]
    s0 = np.take_along_axis(s, first[None], axis=0)[0]
    s1 = np.take_along_axis(s, second[None], axis=0)[0]
    total = s0 + s1
    out = np.zeros((*rgb.shape[:2], len(grass)), np.float32)
    for t in range(len(grass)):
        out[..., t] = np.where(first == t, s0 / total, 0.0) + np.where(second == t, s1 / total, 0.0)
    return out


def patch_reference(vertex_colors: np.ndarray) -> tuple[float, float, float]:
    """A grass type's reference: the HSV of its patch's mean blade colour."""
    mean = np.clip(np.asarray(vertex_colors, np.float64).reshape(-1, 3).mean(axis=0), 0.0, 1.0)
    h, s, v = rgb_to_hsv(mean)
    return float(h), float(s), float(v)


@dataclass(frozen=True)
class SpeciesTuning:
    """What a person sets for one kind: the weights and exponent of its rule and, optionally,
    its own reference colour (HSV); without one the design gives it (`design_rules`)."""

    weights: tuple[float, float, float] = (1.0, 1.0, 1.0)
    exponent: float = 4.0
    reference: tuple[float, float, float] | None = None

    def __post_init__(self) -> None:
        SpeciesRule(self.reference or (0.0, 0.0, 0.0), self.weights, self.exponent)  # checks

    def rule(self, derived: tuple[float, float, float]) -> SpeciesRule:
        return SpeciesRule(self.reference or derived, self.weights, self.exponent)

    def to_dict(self) -> dict:
        out: dict = {"weights": list(self.weights), "exponent": self.exponent}
        if self.reference is not None:
            out["reference"] = list(self.reference)
        return out

    @classmethod
    def from_dict(cls, data: dict) -> SpeciesTuning:
        reference = data.get("reference")
        return cls(
            tuple(float(w) for w in data.get("weights", (1.0, 1.0, 1.0))),  # type: ignore[arg-type]
            float(data.get("exponent", 4.0)),
            None if reference is None else tuple(float(c) for c in reference),  # type: ignore[arg-type]
        )


@dataclass(frozen=True)
class Species:
    """A document's species rules: one tuning per grass type, in the types' order (a type past
    the end takes the defaults), and the soil's."""

    kinds: tuple[SpeciesTuning, ...] = ()
    soil: SpeciesTuning = SpeciesTuning()

    def kind(self, index: int) -> SpeciesTuning:
        return self.kinds[index] if index < len(self.kinds) else SpeciesTuning()

    def to_dict(self) -> dict:
        return {"kinds": [k.to_dict() for k in self.kinds], "soil": self.soil.to_dict()}

    @classmethod
    def from_dict(cls, data: dict) -> Species:
        return cls(
            tuple(SpeciesTuning.from_dict(k) for k in data.get("kinds", [])),
            SpeciesTuning.from_dict(data.get("soil", {})),
        )


def derived_references(document) -> tuple[list[tuple[float, float, float]], tuple]:
    """The references the design gives: each grass type's patch's mean blade colour, the
    light's soil colour."""
    from core.patch import generate_patch

    grass = [
        patch_reference(generate_patch(kind.params).vertices["color"])
        for kind in document.grass_types
    ]
    h, s, v = rgb_to_hsv(np.asarray(document.light.soil_color, np.float64))
    return grass, (float(h), float(s), float(v))


def design_rules(document, species: Species | None = None) -> tuple[list[SpeciesRule], SpeciesRule]:
    """The rules of a document: its species tunings (core/document.py `species`, or those
    given) over the references its design gives."""
    grass, soil = derived_references(document)
    species = species or document.species
    return [species.kind(t).rule(ref) for t, ref in enumerate(grass)], species.soil.rule(soil)


def density_layer(document, rgb: np.ndarray, species: Species | None = None) -> np.ndarray:
    """The density map (rows, columns, channels) with each grass type's channel placed from a
    colour map at the maps' size (rows, columns, 3); channels no type uses kept."""
    grass, soil = design_rules(document, species)
    placed = species_densities(rgb, grass, soil)
    density = document.maps.layer("density").copy()
    for t, kind in enumerate(document.grass_types):
        density[..., kind.channel] = placed[..., t]
    return density
