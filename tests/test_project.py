"""Project files: what a person set round-trips exactly; bad files are refused with a message
naming them; a failed save leaves the old file as it was."""

import dataclasses
import json
import zipfile

import numpy as np
import pytest

from app import project
from app.project import ProjectError, load_project, save_project
from app.scenes import get_scene
from core.lighting import Lighting
from core.lod import LodConfig, LodLevel

SIZE = (160, 100)


@pytest.fixture
def meadow():
    scene = get_scene("meadow")
    return dataclasses.replace(scene, params=scene.params.replace(blade_count=300, seed=42))


def test_a_project_round_trips_what_was_set(tmp_path, meadow):
    path = tmp_path / "meadow.sward"
    maps = meadow.design_maps()
    maps.write("color", 10, 10, np.full((5, 5, 4), 0.25))  # something painted
    lod = LodConfig((LodLevel("geometry", 0, 5), LodLevel("image", 4, None, macro=8)))
    light = Lighting(sun_elevation=20.0, sun_azimuth=300.0, ambient_color=(0.2, 0.3, 0.4))
    scene = dataclasses.replace(
        meadow, lod=lod, slices=meadow.slices.replace(slices=4, top=256), lighting=light
    )
    save_project(path, scene, maps)
    loaded = load_project(path)
    assert loaded.lighting == light
    assert loaded.params == scene.params and loaded.lod == lod and loaded.slices == scene.slices
    assert loaded.grass == tuple(dataclasses.replace(g, density_map=None) for g in scene.grass)
    assert loaded.cameras == scene.cameras and loaded.paths == scene.paths
    assert loaded.grid == scene.grid and loaded.height_scale == scene.height_scale
    assert np.array_equal(loaded.design_maps().stack, maps.stack)
    assert np.array_equal(loaded.terrain().cell_max, scene.terrain().cell_max)
    assert np.array_equal(loaded.prop_boxes(), scene.prop_boxes())


def test_a_reopened_project_renders_the_same_image(tmp_path, headless, ctx, meadow):
    path = tmp_path / "p.sward"
    save_project(path, meadow)
    camera = meadow.camera()
    headless.pipeline.set_only("lod")
    headless.pipeline.set_lod(meadow.lod)
    headless.load(meadow)
    a, sa = headless.render(camera, SIZE)
    headless.load(load_project(path))
    b, sb = headless.render(camera, SIZE)
    headless.load(get_scene("patch-grid"))
    headless.pipeline.set_only("geometry")
    assert (sa.c_g, sa.c_v, sa.c_i, sa.blades) == (sb.c_g, sb.c_v, sb.c_i, sb.blades)
    assert np.abs(a.astype(int) - b.astype(int)).mean() < 1.0


def test_bad_files_are_refused_with_their_name_and_reason(tmp_path, meadow):
    good = tmp_path / "good.sward"
    save_project(good, meadow)
    cases = {}
    cases["text.sward"] = b"just some text"
    cases["truncated.sward"] = good.read_bytes()[: len(good.read_bytes()) // 2]
    for name, data in cases.items():
        (tmp_path / name).write_bytes(data)
    with zipfile.ZipFile(good) as z:
        doc = json.loads(z.read("project.json"))
        maps = z.read("maps.npz")

    def variant(name, change):
        d = json.loads(json.dumps(doc))
        change(d)
        with zipfile.ZipFile(tmp_path / name, "w") as z:
            z.writestr("project.json", json.dumps(d))
            z.writestr("maps.npz", maps)

    variant("future.sward", lambda d: d.update(version=99))
    variant("badparam.sward", lambda d: d["params"].update(blade_count=-5))
    variant("badlight.sward", lambda d: d.update(light={"sun_elevation": 400}))
    variant("nolod.sward", lambda d: d.pop("lod"))
    expected = {
        "text.sward": "not a zip file",
        "truncated.sward": "",
        "future.sward": "version 99",
        "badparam.sward": "blade_count",
        "badlight.sward": "sun elevation",
        "nolod.sward": "lod",
    }
    for name, reason in expected.items():
        with pytest.raises(ProjectError, match=name) as info:
            load_project(tmp_path / name)
        assert reason in str(info.value)
    with pytest.raises(ProjectError, match="no such file"):
        load_project(tmp_path / "missing.sward")


def test_a_failed_save_leaves_the_old_file(tmp_path, meadow, monkeypatch):
    path = tmp_path / "keep.sward"
    save_project(path, meadow)
    before = path.read_bytes()

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(project.np, "savez_compressed", broken)
    with pytest.raises(ProjectError, match=r"cannot save .*keep.sward: disk full"):
        save_project(path, dataclasses.replace(meadow, density=0.5))
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["keep.sward"]  # no temporary left over
