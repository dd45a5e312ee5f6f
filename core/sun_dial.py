"""Where the sun sits on the Light dock's dial, and back: the dial is the sky seen from
above, its centre straight overhead, its rim the horizon, its top the way the view looks
(so a sun dragged to the top lights the grass from behind, one dragged to the right lights
it from the right of the picture)."""

from __future__ import annotations

import math


def camera_heading(yaw: float) -> float:
    """The azimuth (Lighting's convention: 0 = +z, turning towards +x) of the way a camera of
    this yaw looks along the ground: yaw 0 looks along -z (core/camera.py)."""
    return (yaw + 180.0) % 360.0


def dial_point(elevation: float, azimuth: float, heading: float) -> tuple[float, float]:
    """The sun's point in the unit disk (x right, y up) for a view looking along `heading`."""
    r = min(max(1.0 - elevation / 90.0, 0.0), 1.0)
    d = math.radians(azimuth - heading)
    # azimuth grows towards the left of a view that looks along it (right-handed, y up)
    return (-r * math.sin(d), r * math.cos(d))


def dial_sun(x: float, y: float, heading: float) -> tuple[float, float]:
    """Elevation and azimuth (degrees, to a tenth) of the dial's point (x, y); a point outside
    the disk is the horizon in its direction, the centre is overhead facing the view."""
    r = min(math.hypot(x, y), 1.0)
    elevation = round(90.0 * (1.0 - r), 1)
    turn = math.degrees(math.atan2(-x, y)) if r > 0 else 0.0
    azimuth = round((heading + turn) % 360.0, 1) % 360.0
    return elevation, azimuth
