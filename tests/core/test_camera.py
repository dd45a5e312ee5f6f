import numpy as np

from core.camera import Camera, look_at, perspective


def project(m, p):
    h = m @ np.append(p, 1.0)
    return h[:3] / h[3]


def test_target_projects_to_screen_centre():
    cam = Camera.from_eye_target((3.0, 2.0, 5.0), (0.5, 0.0, -1.0))
    assert np.allclose(cam.eye, (3.0, 2.0, 5.0), atol=1e-5)
    m = cam.projection(4 / 3) @ cam.view()
    ndc = project(m, np.array([0.5, 0.0, -1.0]))
    assert np.allclose(ndc[:2], 0.0, atol=1e-5) and -1 < ndc[2] < 1


def test_orbit_keeps_distance_and_zoom_changes_it():
    cam = Camera(distance=6.0)
    cam.orbit(40, 10)
    assert np.isclose(np.linalg.norm(cam.eye - np.asarray(cam.target)), 6.0)
    cam.zoom(0.5)
    assert np.isclose(cam.distance, 3.0)


def test_pan_and_fly_move_the_target():
    cam = Camera()
    before = np.asarray(cam.target)
    cam.pan(0.1, 0.0)
    assert not np.allclose(before, cam.target)
    y = cam.target[1]
    cam.fly(1.0, 0.0)
    assert cam.target[1] == y  # forward stays horizontal


def test_look_at_straight_down_is_finite():
    assert np.all(np.isfinite(look_at((0, 5, 0), (0, 0, 0))))
    assert np.all(np.isfinite(perspective(60, 1.0, 0.1, 100)))
