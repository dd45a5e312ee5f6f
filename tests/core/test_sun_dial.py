import numpy as np
import pytest

from core.camera import Camera
from core.lighting import Lighting
from core.sun_dial import camera_heading, dial_point, dial_sun


@pytest.mark.parametrize("yaw", [0.0, 30.0, 135.0, 250.0])
def test_the_dial_is_oriented_as_the_view_looks(yaw):
    camera = Camera(target=(0.0, 0.0, 0.0), yaw=yaw, pitch=20.0, distance=10.0)
    view = camera.view()
    right, back = view[0, :3], view[2, :3]  # camera axes in world space; it looks along -back
    heading = camera_heading(yaw)
    for (x, y), towards in (
        ((0.8, 0.0), right),  # dragged right: the sun is to the right of the picture
        ((-0.8, 0.0), -right),
        ((0.0, 0.8), -back),  # dragged up: the sun is ahead, the grass is backlit
        ((0.0, -0.8), back),
    ):
        elevation, azimuth = dial_sun(x, y, heading)
        sun = Lighting(sun_elevation=elevation, sun_azimuth=azimuth).sun_direction
        flat = np.array([sun[0], 0.0, sun[2]]) / np.hypot(sun[0], sun[2])
        assert float(flat @ towards) == pytest.approx(np.hypot(towards[0], towards[2]), abs=1e-6)


def test_centre_is_overhead_and_rim_the_horizon():
    assert dial_sun(0.0, 0.0, 40.0)[0] == 90.0
    assert dial_sun(0.0, 1.0, 40.0) == (0.0, 40.0)
    assert dial_sun(3.0, 4.0, 0.0)[0] == 0.0  # outside the disk: on the horizon
    assert dial_sun(0.5, 0.0, 0.0)[0] == pytest.approx(45.0)


@pytest.mark.parametrize("elevation,azimuth,heading", [(50, 135, 0), (5, 300, 210), (80, 10, 350)])
def test_a_sun_comes_back_from_its_point(elevation, azimuth, heading):
    x, y = dial_point(elevation, azimuth, heading)
    assert dial_sun(x, y, heading) == pytest.approx((elevation, azimuth), abs=0.1)
