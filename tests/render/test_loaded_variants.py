"""What a changed project file loads as also renders: variants of a valid project with numbers
moved within and past their ranges either are refused or give a sane frame (finite timings,
counts that add up, no GL error)."""

import dataclasses
import math
import random

import numpy as np

from app.scenes import get_scene
from core.project_file import ProjectError, load_project, save_project
from tests.project_files import leaves, project_parts, replaced
from tests.project_files import write_project as write

SIZE = (64, 48)


def test_variants_that_load_render_a_sane_frame(headless, tmp_path):
    scene = get_scene("patch-grid")
    scene = dataclasses.replace(scene, params=scene.params.replace(blade_count=200))
    good = tmp_path / "good.sward"
    save_project(good, scene.document())
    data, maps = project_parts(good)
    numbers = [p for p in leaves(data) if isinstance(_get(data, p), int | float)]
    numbers = [p for p in numbers if not isinstance(_get(data, p), bool)]
    rng = random.Random(11)
    rendered = refused = 0
    for n, where in enumerate(rng.sample(numbers, 40)):
        value = _get(data, where) * rng.choice([0.5, 0.9, 1.1, 2.0, -1.0]) + rng.choice([0, 1])
        path = tmp_path / f"v{n}.sward"
        write(path, replaced(data, where, value), maps)
        try:
            doc = load_project(path)
        except ProjectError:
            refused += 1
            continue
        if rendered >= 8:
            continue
        image, stats = headless(doc).render(doc.camera(), SIZE)
        assert image.shape == (SIZE[1], SIZE[0], 3) and image.dtype == np.uint8
        assert all(math.isfinite(v) for v in (stats.t_a_ms, stats.t_g_ms, stats.t_v_ms))
        assert image.std() > 1.0  # a picture: sky, ground or grass, not one flat colour
        rendered += 1
    assert rendered >= 4 and refused >= 4


def _get(data, where):
    node = data
    for key in where:
        node = node[key]
    return node
