"""Camera maths: view and projection matrices, and an orbit / fly camera model.

Matrices are numpy float32 4×4 in the usual column-vector convention (clip = P · V · world);
upload them to GL transposed (row-major bytes → GLSL column-major) with `gl_bytes`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def _cross(a, b) -> tuple[float, float, float]:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _unit(v, what: str) -> tuple[float, float, float]:
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if n < 1e-12:
        raise ValueError(what)
    return (v[0] / n, v[1] / n, v[2] / n)


# The view and projection are made every frame: plain float arithmetic here, one array at the
# end, rather than a dozen small numpy operations, each with its call overhead.
def look_at(eye, target, up=(0.0, 1.0, 0.0)) -> np.ndarray:
    e, t = _vec3(eye), _vec3(target)
    f = _unit((t[0] - e[0], t[1] - e[1], t[2] - e[2]), "camera eye and target are the same point")
    up = _vec3(up)
    if abs(f[0] * up[0] + f[1] * up[1] + f[2] * up[2]) > 0.9999:  # straight up or down
        up = (0.0, 0.0, -1.0)
    s = _unit(_cross(f, up), "camera up is parallel to the view")
    u = _cross(s, f)
    return np.array(
        [
            [s[0], s[1], s[2], -(s[0] * e[0] + s[1] * e[1] + s[2] * e[2])],
            [u[0], u[1], u[2], -(u[0] * e[0] + u[1] * e[1] + u[2] * e[2])],
            [-f[0], -f[1], -f[2], f[0] * e[0] + f[1] * e[1] + f[2] * e[2]],
            [0.0, 0.0, 0.0, 1.0],
        ],
        np.float32,
    )


def perspective(fov_y_deg: float, aspect: float, near: float, far: float) -> np.ndarray:
    f = 1.0 / math.tan(math.radians(fov_y_deg) / 2.0)
    return np.array(
        [
            [f / aspect, 0.0, 0.0, 0.0],
            [0.0, f, 0.0, 0.0],
            [0.0, 0.0, (far + near) / (near - far), 2.0 * far * near / (near - far)],
            [0.0, 0.0, -1.0, 0.0],
        ],
        np.float32,
    )


def _vec3(v) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def gl_bytes(m: np.ndarray) -> bytes:
    """Bytes of a 4×4 matrix in the column-major order GLSL expects."""
    return np.ascontiguousarray(m.T, dtype=np.float32).tobytes()


@dataclass
class Camera:
    """An orbit camera around a target; fly mode moves eye and target together.

    yaw turns about +y (0 looks along -z), pitch is the elevation of the eye above the target
    in degrees, distance the eye-target distance in world units (one patch cell = 1).
    """

    target: tuple[float, float, float] = (0.0, 0.0, 0.0)
    yaw: float = 30.0
    pitch: float = 25.0
    distance: float = 8.0
    fov_y: float = 50.0
    near: float = 0.02
    far: float = 500.0

    @classmethod
    def from_eye_target(cls, eye, target, **kw) -> Camera:
        eye = np.asarray(eye, dtype=np.float64)
        target = np.asarray(target, dtype=np.float64)
        d = eye - target
        dist = float(np.linalg.norm(d))
        if dist < 1e-9:
            raise ValueError("camera eye and target are the same point")
        pitch = float(np.degrees(np.arcsin(np.clip(d[1] / dist, -1, 1))))
        yaw = float(np.degrees(np.arctan2(d[0], d[2])))
        return cls(target=_vec3(target), yaw=yaw, pitch=pitch, distance=dist, **kw)

    @property
    def eye(self) -> np.ndarray:
        yaw, pitch = math.radians(self.yaw), math.radians(self.pitch)
        d, (x, y, z) = self.distance, _vec3(self.target)
        return np.array(
            [
                x + d * (math.sin(yaw) * math.cos(pitch)),
                y + d * math.sin(pitch),
                z + d * (math.cos(yaw) * math.cos(pitch)),
            ]
        )

    def view(self) -> np.ndarray:
        return look_at(self.eye, self.target)

    def projection(self, aspect: float) -> np.ndarray:
        return perspective(self.fov_y, aspect, self.near, self.far)

    def orbit(self, d_yaw: float, d_pitch: float) -> None:
        self.yaw = (self.yaw + d_yaw) % 360.0
        self.pitch = float(np.clip(self.pitch + d_pitch, -5.0, 89.0))

    def zoom(self, factor: float) -> None:
        self.distance = float(np.clip(self.distance * factor, 0.05, 400.0))

    def pan(self, dx: float, dy: float) -> None:
        """Move the target in the view plane by fractions of the distance."""
        v = self.view()
        right, up = v[0, :3].astype(np.float64), v[1, :3].astype(np.float64)
        shift = (right * dx + up * dy) * self.distance
        self.target = _vec3(np.asarray(self.target) + shift)

    def fly(self, forward: float, strafe: float, rise: float = 0.0) -> None:
        """Move eye and target together along the horizontal view direction (WASD)."""
        yaw = np.radians(self.yaw)
        ahead = -np.array([np.sin(yaw), 0.0, np.cos(yaw)])
        right = np.array([np.cos(yaw), 0.0, -np.sin(yaw)])
        shift = ahead * forward + right * strafe + np.array([0.0, rise, 0.0])
        self.target = _vec3(np.asarray(self.target) + shift)


def orthographic(left: float, right: float, bottom: float, top: float, near: float, far: float):
    m = np.identity(4)
    m[0, 0] = 2.0 / (right - left)
    m[1, 1] = 2.0 / (top - bottom)
    m[2, 2] = -2.0 / (far - near)
    m[0, 3] = -(right + left) / (right - left)
    m[1, 3] = -(top + bottom) / (top - bottom)
    m[2, 3] = -(far + near) / (far - near)
    return m.astype(np.float32)
