"""Picking the ground under the cursor: rays through pixels hit the terrain where a point
projects, on flat and hilly ground."""

import numpy as np
import pytest

from core.camera import Camera
from core.heights import hills
from core.picking import ground_circle, ground_height, ground_hit, pixel_ray, world_to_texel
from core.terrain import Terrain


def project(camera, point, w, h):
    clip = camera.projection(w / h) @ camera.view() @ np.append(point, 1.0)
    ndc = clip[:3] / clip[3]
    return (ndc[0] + 1) / 2 * w, (1 - ndc[1]) / 2 * h


@pytest.mark.parametrize("scale", [0.0, 3.0])
def test_the_ray_through_a_points_pixel_hits_that_point(scale):
    terrain = Terrain.centred(32, 24, heights=hills(128, seed=3), height_scale=scale)
    camera = Camera.from_eye_target((4.0, 14.0, 20.0), (0.0, 0.0, 0.0))
    for x, z in [(0.0, 0.0), (-6.5, 3.2), (9.0, -7.5)]:
        point = np.array([x, float(ground_height(terrain, x, z)), z])
        px, py = project(camera, point, 640, 480)
        hit = ground_hit(terrain, *pixel_ray(camera, px, py, 640, 480))
        assert hit is not None
        assert np.linalg.norm(hit - point) < 0.05


def test_a_ray_into_the_sky_or_beside_the_terrain_misses():
    terrain = Terrain.centred(8, 8)
    camera = Camera.from_eye_target((0.0, 3.0, 10.0), (0.0, 0.0, 0.0))
    assert ground_hit(terrain, *pixel_ray(camera, 320, 2, 640, 480)) is None  # sky
    assert ground_hit(terrain, np.array([20.0, 5.0, 0.0]), np.array([0.0, -1.0, 0.0])) is None


def test_texels_and_circles_follow_the_terrain():
    terrain = Terrain.centred(16, 16, heights=hills(64, seed=1), height_scale=2.0)
    assert world_to_texel(terrain, (256, 128), -8.0, -8.0) == (0.0, 0.0)
    assert world_to_texel(terrain, (256, 128), 0.0, 0.0) == (128.0, 64.0)
    ring = ground_circle(terrain, 1.0, 2.0, 3.0)
    assert np.allclose(np.hypot(ring[:, 0] - 1.0, ring[:, 2] - 2.0), 3.0, atol=1e-4)
    assert np.allclose(ring[:, 1], ground_height(terrain, ring[:, 0], ring[:, 2]) + 0.02, atol=1e-4)


def test_picking_follows_a_height_map_newer_than_the_terrain():
    flat = np.zeros((64, 64), np.float32)
    terrain = Terrain.centred(16, 16, heights=flat, height_scale=2.0)
    raised = flat.copy()
    raised[24:40, 24:40] = 1.0  # a plateau painted 2 units up, the terrain not rebuilt yet
    camera = Camera.from_eye_target((0.0, 12.0, 0.01), (0.0, 0.0, 0.0))
    ray = pixel_ray(camera, 320, 240, 640, 480)
    assert ground_hit(terrain, *ray)[1] == pytest.approx(0.0, abs=0.02)
    assert ground_hit(terrain, *ray, heights=raised)[1] == pytest.approx(2.0, abs=0.02)
