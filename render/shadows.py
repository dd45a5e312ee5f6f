"""Blade shadows on the ground (core/shadows.py, Papavasiliou 3.6): the blades of the geometry
level drawn a second time onto the ground along the sun (shaders/geometry.glsl, SHADOW), and
the ground beyond them darkened where the blades' shadows would fall (shaders/ground.glsl,
SHADOWS), from each grass type's field of its patch's shadows for the sun of the frame."""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import TYPE_CHECKING

import moderngl
import numpy as np

from core.lod import NO_FADE
from core.patch import GrassPatch
from core.shadows import STRETCHES, field, reach
from render.ground import MAX_TYPES
from render.uniforms import SHADOW_UNIT, set_uniforms

if TYPE_CHECKING:
    from render.frame import FramePipeline
    from render.uniforms import FrameUniforms

# per patch, the last few suns' fields (a drag of the sun dial asks for one after another)
_fields: weakref.WeakKeyDictionary[GrassPatch, dict] = weakref.WeakKeyDictionary()


def patch_field(patch: GrassPatch, sun: np.ndarray, mirrored: bool, uneven: bool) -> np.ndarray:
    """core/shadows.py field, kept for the patch and sun: on `uneven` ground at STRETCHES,
    else on level ground alone."""
    kept = _fields.setdefault(patch, {})
    key = (tuple(round(float(v), 6) for v in sun), mirrored, uneven)
    if key not in kept:
        if len(kept) >= 8:
            kept.pop(next(iter(kept)))
        kept[key] = field(patch, sun, mirrored, STRETCHES if uneven else (1.0,))
    return kept[key]


_reaches: weakref.WeakKeyDictionary[GrassPatch, float] = weakref.WeakKeyDictionary()


def patch_reach(patch: GrassPatch) -> float:
    """core/shadows.py reach, kept for the patch (it does not change with the sun)."""
    if patch not in _reaches:
        _reaches[patch] = reach(patch)
    return _reaches[patch]


@dataclass(frozen=True)
class GroundShadows:
    """shaders/ground.glsl's SHADOWS uniforms for one view."""

    fields: tuple[np.ndarray, ...]  # per type, core/shadows.py field
    reach: tuple[float, ...]  # core/shadows.py reach per type
    channels: tuple[int, ...]
    spans: tuple[tuple[float, float], ...]  # where each type's geometry draws blades
    fades: tuple[tuple[float, float, float, float], ...]
    strength: float
    density: float

    def layers(self) -> np.ndarray:
        """The fields one after the other as a texture array's RGBA8 layers (FIELD × FIELD
        each), so that one read gives what the ground interpolates between: per type, mirror
        state, pair of neighbouring stretches (a, b) and density step j, the shares at
        (x_j, a), (x_j+1, a), (x_j, b), (x_j+1, b)."""
        out = []
        for f in self.fields:
            states, stretches = f.shape[:2]
            pairs = [(a, a + 1) for a in range(stretches - 1)] or [(0, 0)]
            for state in range(states):
                for a, b in pairs:
                    step = np.stack(
                        [f[state, a, :-1], f[state, a, 1:], f[state, b, :-1], f[state, b, 1:]],
                        axis=-1,
                    )  # (samples − 1, rows, cols, 4)
                    out.append(step)
        return np.round(np.clip(np.concatenate(out), 0.0, 1.0) * 255.0).astype(np.uint8)

    def apply(self, program: moderngl.Program, field: moderngl.TextureArray) -> None:
        """Set the uniforms; `field` holds `layers()` with their mipmaps."""
        n = len(self.channels)
        field.use(SHADOW_UNIT)
        spans = [(a, min(b, 1e30), 0.0, 0.0) for a, b in self.spans]
        spans += [(1.0, 0.0, 0.0, 0.0)] * (MAX_TYPES - n)  # none: no blades anywhere
        fades = list(self.fades) + [NO_FADE] * (MAX_TYPES - n)
        states, stretches = self.fields[0].shape[:2]
        values = {
            "u_shadow_types": n,
            "u_shadow_field": SHADOW_UNIT,
            "u_shadow_states": states,
            "u_shadow_stretches": stretches,
            "u_shadow_channel": np.eye(4, dtype=np.float32)[
                (list(self.channels) + [0] * 4)[:4]
            ].tobytes(),
            "u_shadow_span": np.array(spans, np.float32).tobytes(),
            "u_shadow_fade": np.array(fades, np.float32).tobytes(),
            "u_shadow_density": self.density,
            "u_shadow_strength": self.strength,
            "u_shadow_reach": np.array(
                list(self.reach) + [0.0] * (MAX_TYPES - n), np.float32
            ).tobytes(),
        }
        set_uniforms(program, values)


def ground_shadows(p: FramePipeline, frame: FrameUniforms, cells: list) -> GroundShadows | None:
    """What the ground needs to darken where no blades cast shadows, or None: shadows off."""
    light = frame.light
    if not light.blade_shadows:
        return None
    sun = light.sun_direction
    fields, reaches, channels, spans, fades = [], [], [], [], []
    # a draft answers a new sun with the field of level ground alone (a slope then stretches
    # it as a union of shadows dropped at random grows): a third of the work
    uneven = frame.height_scale > 0 and not frame.draft
    for grass, view in list(zip(p.grass_types, cells, strict=True))[:MAX_TYPES]:
        patch = grass.patch
        if patch is None:
            continue
        fields.append(patch_field(patch, sun, frame.tiling, uneven))
        reaches.append(patch_reach(patch))
        channels.append(grass.density_channel)
        spans.append(view.blades if view.blades is not None else (1.0, 0.0))
        fades.append(view.fades.get(("geometry", 0), NO_FADE))
    if not fields:
        return None
    return GroundShadows(
        tuple(fields), tuple(reaches), tuple(channels), tuple(spans), tuple(fades),
        light.shadow_strength, float(p.density),
    )  # fmt: skip


def draw_blade_shadows(p: FramePipeline, frame: FrameUniforms, drawn: list) -> None:
    """Each grass type's blades of this view again, as their shadows on the ground: drawn
    over it (pushed back in depth, render/ground.py) without writing depth, so that the volume
    after them still meets the ground's."""
    soil = p.ground.soil_uniforms(frame.light)
    p.ctx.fbo.depth_mask = False
    for grass, batches in zip(p.grass_types, drawn, strict=True):
        if ("geometry", 0) not in batches or grass.geometry.vao is None:
            continue
        renderer = grass.geometry
        renderer.prepare(frame, ("SHADOW",))
        for name, value in soil.items():
            renderer.program[name].value = value
        renderer.program["u_shadow_strength"].value = frame.light.shadow_strength
        renderer.draw_coarsest()
        renderer.finalize()
    p.ctx.fbo.depth_mask = True
