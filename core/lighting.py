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

    @property
    def sun_direction(self) -> np.ndarray:
        """Unit vector towards the sun."""
        el, az = np.radians(self.sun_elevation), np.radians(self.sun_azimuth)
        return np.array([np.cos(el) * np.sin(az), np.sin(el), np.cos(el) * np.cos(az)])
