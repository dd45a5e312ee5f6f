"""View-frustum culling after thesis 6.1.4 (Picco 2003): the frustum is approximated by a sphere
around it and a cone from the eye; a bounding sphere is culled when it misses either. Both tests
are conservative: they never cull a sphere that meets the frustum."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Frustum:
    eye: np.ndarray
    forward: np.ndarray  # unit view direction
    centre: np.ndarray  # of the sphere around the frustum
    radius: float
    sin_angle: float  # the cone's half angle, precomputed (6.1.4)
    cos_angle: float

    @classmethod
    def from_view(cls, eye, target, fov_y: float, aspect: float, near: float, far: float):
        eye = np.asarray(eye, np.float64)
        forward = np.asarray(target, np.float64) - eye
        forward /= np.linalg.norm(forward)
        tan_y = math.tan(math.radians(fov_y) / 2.0)
        tan_x = tan_y * aspect
        centre = eye + forward * (near + far) / 2.0
        # the far plane's corner: distance far along the view, far·tan sideways and up
        corner_offset = far * math.hypot(tan_x, tan_y)
        radius = math.hypot(corner_offset, (far - near) / 2.0)
        angle = math.atan(math.hypot(tan_x, tan_y))
        return cls(eye, forward, centre, radius, math.sin(angle), math.cos(angle))

    @classmethod
    def from_camera(cls, camera, aspect: float) -> Frustum:
        return cls.from_view(
            camera.eye, camera.target, camera.fov_y, aspect, camera.near, camera.far
        )

    def visible(self, centres: np.ndarray, radii: np.ndarray) -> np.ndarray:
        """Which spheres (centres (n, 3), radii (n,)) may meet the frustum."""
        near_sphere = np.sum((centres - self.centre) ** 2, axis=1) <= (radii + self.radius) ** 2
        return near_sphere & self._cone(centres, radii)

    def _cone(self, s: np.ndarray, r: np.ndarray) -> np.ndarray:
        """Sphere against the infinite cone (Eberly 2002, "Intersection of a sphere and a
        cone")."""
        d_axis = self.forward
        u = self.eye[None, :] - (r / self.sin_angle)[:, None] * d_axis[None, :]
        d = s - u
        d_len2 = np.sum(d * d, axis=1)
        e = d @ d_axis
        in_extended = (e > 0) & (e * e >= d_len2 * self.cos_angle**2)
        d = s - self.eye
        d_len2 = np.sum(d * d, axis=1)
        e = -(d @ d_axis)
        behind_apex = (e > 0) & (e * e >= d_len2 * self.sin_angle**2)
        return in_extended & (~behind_apex | (d_len2 <= r * r))
