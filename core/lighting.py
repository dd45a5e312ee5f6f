"""The scene's light: one directional sun plus ambient (thesis 6.4.3)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Lighting:
    sun_elevation: float = 50.0  # degrees above the horizon
    sun_azimuth: float = 135.0  # degrees, 0 = +z, turning towards +x
    sun_color: tuple[float, float, float] = (1.0, 0.96, 0.86)
    ambient_color: tuple[float, float, float] = (0.36, 0.42, 0.52)
    translucency: float = 0.35
    blade_ao_impact: float = 0.6  # B_impact (eq. 6.11): how dark the dense grass gets at the roots
    blade_ao_height: float = 0.3  # B_height (eq. 6.11): up to which height, world units
    sky_color: tuple[float, float, float] = (0.62, 0.75, 0.90)
    soil_color: tuple[float, float, float] = (0.30, 0.25, 0.17)
    fog_distance: float = 160.0
    # blades cast shadows on the ground along the sun (Papavasiliou 3.6, core/shadows.py): how
    # much of the sun's light a blade's shadow takes (its screen-door coverage)
    blade_shadows: bool = False
    shadow_strength: float = 0.6

    def __post_init__(self) -> None:
        if not -10.0 <= self.sun_elevation <= 90.0:
            raise ValueError(f"sun elevation {self.sun_elevation:g}° is out of range; -10 … 90")
        for name in ("sun_color", "ambient_color", "sky_color", "soil_color"):
            colour = getattr(self, name)
            if len(colour) != 3 or not all(0.0 <= c <= 4.0 for c in colour):
                raise ValueError(f"{name} must be three values in 0 … 4, got {colour}")
        if not isinstance(self.blade_shadows, bool):
            raise ValueError("blade_shadows must be true or false")
        for name in ("translucency", "blade_ao_impact", "shadow_strength"):
            if not 0.0 <= getattr(self, name) <= 1.0:
                raise ValueError(f"{name} = {getattr(self, name):g} is out of range; 0 … 1")
        if self.blade_ao_height <= 0 or self.fog_distance <= 0:
            raise ValueError("blade AO height and fog distance must be positive")

    @property
    def sun_direction(self) -> np.ndarray:
        """Unit vector towards the sun."""
        el, az = np.radians(self.sun_elevation), np.radians(self.sun_azimuth)
        return np.array([np.cos(el) * np.sin(az), np.sin(el), np.cos(el) * np.cos(az)])
