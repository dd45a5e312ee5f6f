"""Per-frame uniforms shared by every program: camera and light."""

from __future__ import annotations

from dataclasses import dataclass, field

import moderngl
import numpy as np

from core.camera import gl_bytes
from core.lighting import Lighting
from core.wind import NOISE_FEATURES, Wind
from render.shaders import reads, wind_defines

DESIGN_UNIT = 7  # texture unit of the design-map stack (render/design_maps.py)
# units of the height + density textures, one a density channel (DesignMapTextures.grounds)
GROUND_UNIT = 8
TILING_UNIT = 5  # the aperiodic tiling's noise map (render/tiling.py)
WIND_UNIT = 13  # the wind's noise map (render/wind.py)
SINK_UNIT = 14  # how far the ground mesh's vertices sink (render/ground.py)
FAR_DESIGN_UNIT = 15  # the colour map, mipmapped (render/design_maps.py)
SHADOW_UNIT = 16  # the blades' shadow fields, every grass type's (render/shadows.py)


@dataclass
class FrameUniforms:
    """Camera, light and view mode; renderers add their own uniforms on top."""

    view_proj: np.ndarray
    eye: np.ndarray
    light: Lighting
    technique_view: bool = False
    viewport_height: int = 1  # pixels, for the volume renderer's mip level
    fov_y: float = 50.0  # degrees
    height_scale: float = 0.0  # world units of the height map's 1 (thesis 6.4.4)
    tiling: bool = False  # cells mirrored by the terrain's noise map (render/tiling.py)
    wind: Wind = field(default_factory=Wind)  # the wind over the terrain (core/wind.py)
    time: float = 0.0  # seconds: the moment of the wind drawn
    wind_view: bool = False  # the grass coloured by its lean (--view wind)
    # a draft (render/frame.py draft): the light tables may still be of the patch before an
    # edit, rebuilt for the full frame that follows (render/facing.py)
    draft: bool = False
    # whether the ambient or the diffuse light map has been painted (DesignMapTextures
    # light_maps): programs read them only then
    light_maps: bool = False
    # the most the trample map lays grass over (DesignMapTextures trample_lean): 0, nowhere
    trample_lean: float = 0.0

    @property
    def trampled(self) -> bool:
        return self.trample_lean > 0.0

    @property
    def defines(self) -> tuple[str, ...]:
        """The defines of the program variants this frame draws with: the wind's and the
        trampling's (render/shaders.py wind_defines) and LIGHT_MAPS where the light maps are
        painted."""
        light = ("LIGHT_MAPS",) if self.light_maps else ()
        return wind_defines(self.wind.enabled, self.trampled) + light

    def apply(self, program: moderngl.Program, technique_color=(0.0, 0.0, 0.0)) -> None:
        """Set every frame uniform the program uses (others are skipped)."""
        values = {
            "u_view_proj": gl_bytes(self.view_proj),
            "u_eye": tuple(float(x) for x in self.eye),
            "u_light_dir": tuple(float(x) for x in self.light.sun_direction),
            "u_light_color": self.light.sun_color,
            "u_ambient_color": self.light.ambient_color,
            "u_translucency": self.light.translucency,
            "u_ao_impact": self.light.blade_ao_impact,
            "u_ao_height": self.light.blade_ao_height,
            "u_design": DESIGN_UNIT,
            "u_trample": DESIGN_UNIT,
            "u_design_far": FAR_DESIGN_UNIT,
            "u_height_scale": float(self.height_scale),
            "u_technique_view": 1.0 if self.technique_view else 0.0,
            "u_technique_color": tuple(technique_color),
            "u_tiling": 1.0 if self.tiling else 0.0,
            "u_tiling_noise": TILING_UNIT,
            "u_wind_view": 1.0 if self.wind_view else 0.0,
            **wind_uniforms(self.wind, self.time),
        }
        set_uniforms(program, values)


def set_uniforms(program: moderngl.Program, values: dict[str, object]) -> None:
    """Each value the program reads (bytes: written whole, an array or matrix); others skipped."""
    for name, value in values.items():
        if not reads(program, name):
            continue
        if isinstance(value, bytes):
            program[name].write(value)
        else:
            program[name].value = value


def wind_uniforms(wind: Wind, time: float) -> dict[str, object]:
    """shaders/_wind.glsl's uniforms: the patterns' travel wrapped to one repeat of the noise
    map, so that float32 keeps its precision however long the wind has blown."""
    gust_tile = wind.gust_scale * NOISE_FEATURES
    turbulence_tile = wind.turbulence_scale * NOISE_FEATURES
    gust, turbulence = wind.offsets(time)
    return {
        "u_wind_noise": WIND_UNIT,
        "u_wind_heading": tuple(float(v) for v in wind.heading),
        "u_gust_shift": tuple(float(v) for v in gust % gust_tile),
        "u_turbulence_shift": tuple(float(v) for v in turbulence % turbulence_tile),
        "u_gust_strength": wind.gust_strength,
        "u_gust_tile": gust_tile,
        "u_turbulence_strength": wind.turbulence_strength,
        "u_turbulence_tile": turbulence_tile,
    }
