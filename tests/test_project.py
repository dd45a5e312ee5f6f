"""Project files: what a person set round-trips exactly; bad files are refused with a message
naming them; a failed save leaves the old file as it was."""

import dataclasses

import numpy as np
import pytest

from app.scenes import get_scene
from core import project_file
from core.lighting import Lighting
from core.lod import LodConfig, LodLevel
from core.paint_rule import PaintRule
from core.project_file import ProjectError, load_project, save_project
from core.species import Species, SpeciesTuning
from tests.project_files import project_parts, variant

SIZE = (160, 100)


@pytest.fixture
def meadow():
    scene = get_scene("meadow")
    return dataclasses.replace(scene, params=scene.params.replace(blade_count=300, seed=42))


def test_a_project_round_trips_what_was_set(tmp_path, meadow):
    path = tmp_path / "meadow.sward"
    doc = meadow.document()
    doc.maps.write("color", 10, 10, np.full((5, 5, 4), 0.25))  # something painted
    doc.set_lod(
        0,
        LodConfig(
            (LodLevel("geometry", 0, 5), LodLevel("image", 4, None, macro=8)),
            view_height=540,
            segment_tolerance=2.0,
        ),
    )
    doc.light = Lighting(sun_elevation=20.0, sun_azimuth=300.0, ambient_color=(0.2, 0.3, 0.4))
    doc.slices = doc.slices.replace(slices=4, top=256)
    doc.species = Species(
        (SpeciesTuning((2.0, 0.5, 0.0), 8.0, (0.3, 0.6, 0.5)),), SpeciesTuning(exponent=2.0)
    )
    doc.paint_rule = PaintRule(slope=(0.0, 20.0), height=(1.5, 9.0), soft_height=0.5)
    save_project(path, doc)
    loaded = load_project(path)
    assert loaded.same_as(doc)
    assert np.array_equal(loaded.terrain.cell_max, doc.terrain.cell_max)
    assert np.array_equal(loaded.prop_boxes(), doc.prop_boxes())
    assert [p.shape for p in loaded.props] == ["rock"] * 3  # the meadow's rocks stay rocks


def test_a_reopened_project_renders_the_same_image_with_its_lod(tmp_path, headless, meadow):
    """The LOD levels come with the project: a reopened project with edited levels draws what
    the edited document drew, not what the scene's own levels draw."""
    path = tmp_path / "p.sward"
    doc = meadow.document()
    camera = doc.camera()
    before, s0 = headless(doc).render(camera, SIZE)
    doc.set_lod(0, LodConfig((LodLevel("geometry", 0, 12), LodLevel("image", 9, None, macro=4))))
    a, sa = headless(doc).render(camera, SIZE)
    save_project(path, doc)
    b, sb = headless(load_project(path)).render(camera, SIZE)
    assert (sa.c_g, sa.c_v, sa.c_i, sa.blades) == (sb.c_g, sb.c_v, sb.c_i, sb.blades)
    assert np.array_equal(a, b)
    assert (s0.c_g, s0.c_v, s0.c_i) != (sa.c_g, sa.c_v, sa.c_i)  # the edit mattered
    assert np.abs(before.astype(int) - a.astype(int)).max() > 20


def test_bad_files_are_refused_with_their_name_and_reason(tmp_path, meadow):
    good = tmp_path / "good.sward"
    save_project(good, meadow.document())
    cases = {}
    cases["text.sward"] = b"just some text"
    cases["truncated.sward"] = good.read_bytes()[: len(good.read_bytes()) // 2]
    for name, data in cases.items():
        (tmp_path / name).write_bytes(data)
    data, maps = project_parts(good)
    variant(tmp_path / "future.sward", data, maps, lambda d: d.update(version=99))
    variant(tmp_path / "badparam.sward", data, maps, lambda d: d["params"].update(blade_count=-5))
    variant(
        tmp_path / "badlight.sward", data, maps, lambda d: d.update(light={"sun_elevation": 400})
    )
    variant(tmp_path / "nolod.sward", data, maps, lambda d: d.pop("lod"))
    variant(tmp_path / "badview.sward", data, maps, lambda d: d["lod"].update(view_height=4))
    expected = {
        "text.sward": "not a zip file",
        "truncated.sward": "",
        "future.sward": "version 99",
        "badparam.sward": "params.blade_count: expected `int` >= 1",
        "badlight.sward": "light.sun_elevation: expected `float` <= 90",
        "nolod.sward": "missing required field `lod`",
        "badview.sward": "lod.view_height: expected `float` >= 16",
    }
    for name, reason in expected.items():
        with pytest.raises(ProjectError, match=name) as info:
            load_project(tmp_path / name)
        assert reason in str(info.value)
    with pytest.raises(ProjectError, match="no such file"):
        load_project(tmp_path / "missing.sward")


def test_a_failed_save_leaves_the_old_file(tmp_path, meadow, monkeypatch):
    path = tmp_path / "keep.sward"
    doc = meadow.document()
    save_project(path, doc)
    before = path.read_bytes()

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(project_file.np, "savez_compressed", broken)
    doc.density = 0.5
    with pytest.raises(ProjectError, match=r"cannot save .*keep.sward: disk full"):
        save_project(path, doc)
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["keep.sward"]  # no temporary left over


def test_saving_through_a_link_writes_its_target_and_clears_old_temporaries(tmp_path, meadow):
    import os
    import time

    real = tmp_path / "real.sward"
    doc = meadow.document()
    save_project(real, doc)
    link = tmp_path / "link.sward"
    link.symlink_to(real)
    stale = tmp_path / ".real.sward.abc123.tmp"  # left by a save that was killed
    stale.write_bytes(b"half a file")
    old = time.time() - 3600
    os.utime(stale, (old, old))
    doc.density = 0.25
    save_project(link, doc)
    assert link.is_symlink()  # the link stays a link ...
    assert load_project(real).density == 0.25  # ... and the file it points to was written
    assert not stale.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.sward", "real.sward"]


def test_a_save_killed_at_any_moment_leaves_the_old_or_the_new_file(tmp_path, meadow):
    """kill -9 of a process saving in a loop: the file always loads, as the old version or the
    new one, and the next save clears what the killed ones left."""
    import os
    import signal
    import subprocess
    import sys
    import time

    path = tmp_path / "p.sward"
    save_project(path, meadow.document())
    script = (
        "import sys\n"
        "from app.scenes import get_scene\n"
        "from core.project_file import save_project\n"
        "doc = get_scene('patch-grid').document()\n"
        "print('saving', flush=True)\n"
        "for i in range(10**6):\n"
        "    doc.density = (i % 10) / 10\n"
        "    save_project(sys.argv[1], doc)\n"
    )
    for delay in (0.0, 0.05, 0.1, 0.15, 0.2):
        saver = subprocess.Popen(
            [sys.executable, "-c", script, str(path)], stdout=subprocess.PIPE, text=True
        )
        assert saver.stdout.readline() == "saving\n"  # the loop runs
        time.sleep(delay)
        saver.send_signal(signal.SIGKILL)
        saver.wait()
        saver.stdout.close()
        loaded = load_project(path)  # never a torn file
        assert 0.0 <= loaded.density <= 1.0
    old = time.time() - 3600  # what the killed saves left is stale by now
    for leftover in tmp_path.glob(".p.sward.*.tmp"):
        os.utime(leftover, (old, old))
    save_project(path, meadow.document())
    assert [p.name for p in tmp_path.iterdir()] == ["p.sward"]
