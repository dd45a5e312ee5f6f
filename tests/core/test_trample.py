"""Trampled grass in core: the map's encoding, the lean it adds to the wind's, the brush that
paints it along a stroke, and project files with and without it."""

import io
import zipfile

import numpy as np
import pytest

from core.brush import Brush, Stroke
from core.design_maps import DesignMaps
from core.trample import brush_value, decode, encode, lean_at, trampled
from core.wind import MAX_LEAN, Wind, grass_lean, lean


def test_a_lean_survives_the_maps_encoding_and_stays_within_the_largest():
    leans = np.array([[0.0, 0.0], [0.3, -0.2], [-0.9, 0.0], [2.0, 2.0]])
    back = decode(encode(leans))
    assert np.allclose(back[:3], leans[:3])
    assert np.isclose(np.linalg.norm(back[3]), MAX_LEAN)  # limited, its direction kept
    assert np.allclose(back[3] / np.linalg.norm(back[3]), [2**-0.5, 2**-0.5])
    assert np.all((encode(leans) >= 0) & (encode(leans) <= 1))


def test_the_brush_value_lays_the_grass_the_way_it_names():
    assert np.allclose(decode(np.array(brush_value(0.6, 90.0))), [0.0, 0.6], atol=1e-12)
    assert np.allclose(decode(np.array(brush_value(0.5, 180.0))), [-0.5, 0.0], atol=1e-12)
    assert brush_value(0.0, 33.0) == (0.5, 0.5)


def test_the_trampled_lean_adds_to_the_winds_no_further_than_the_largest():
    wind = Wind(enabled=True, gust_strength=0.5, turbulence_strength=0.0)
    xz = np.array([[3.0, 4.0], [10.0, -2.0]])
    trample = np.array([[0.2, 0.0], [0.0, 0.0]])
    total = grass_lean(wind, xz, 1.0, trample)
    assert np.allclose(total[1], lean(wind, xz, 1.0)[1])  # nothing trampled: the wind's
    assert np.linalg.norm(total[0] - lean(wind, xz, 1.0)[0]) > 0.05
    assert np.all(
        np.linalg.norm(grass_lean(wind, xz, 1.0, trample * 10), axis=-1) <= MAX_LEAN + 1e-9
    )
    # still air: the trampled lean alone
    assert np.allclose(grass_lean(Wind(), xz, 0.0, trample), trample)


def test_the_lean_is_read_from_the_map_as_the_gpu_filters_it():
    maps = DesignMaps(8, 4)
    assert not trampled(maps.layer("trample"))
    maps.write("trample", 4, 0, np.broadcast_to(np.array(brush_value(0.8, 0.0)), (4, 4, 2)))
    texels = maps.layer("trample")
    assert trampled(texels)
    u = np.array([1.5 / 8, 6.5 / 8, 4.0 / 8])  # texel centres, and half way across the edge
    v = np.full(3, 0.5)
    got = lean_at(texels, u, v)
    assert np.allclose(got, [[0.0, 0.0], [0.8, 0.0], [0.4, 0.0]], atol=1e-6)


def test_a_stroke_lays_the_grass_along_the_way_it_moves():
    maps = DesignMaps(64)
    brush = Brush(size=8, strength=1.0, value=brush_value(0.6, 0.0), falloff="constant")
    stroke = Stroke(maps, "trample", brush, follow=True)
    stroke.add(10.0, 10.0)  # where it starts: the direction is not known yet
    stroke.add(10.0, 40.0)  # down the rows: along +z
    got = decode(maps.layer("trample")[25, 10])
    assert np.allclose(got, [0.0, 0.6], atol=1e-3)
    assert np.allclose(decode(maps.layer("trample")[10, 10]), [0.0, 0.6], atol=1e-3)
    stroke.finish()
    stroke.undo()
    assert not trampled(maps.layer("trample"))


def test_a_stroke_follows_the_ground_not_the_texels_where_texels_are_not_square():
    maps = DesignMaps(64, 32)  # a square terrain: a texel is twice as deep as it is wide
    brush = Brush(size=4, strength=1.0, value=brush_value(0.5, 0.0), falloff="constant")
    stroke = Stroke(maps, "trample", brush, follow=True, texel=(1.0, 2.0))
    stroke.add(10.0, 10.0)
    stroke.add(20.0, 20.0)  # 10 texels each way: twice as far along z as along x
    got = decode(maps.layer("trample")[15, 15])
    assert np.isclose(np.degrees(np.arctan2(got[1], got[0])), np.degrees(np.arctan2(2.0, 1.0)))
    assert np.isclose(np.linalg.norm(got), 0.5, atol=1e-3)


def test_a_project_keeps_the_trample_map_and_one_written_before_it_opens_upright(tmp_path):
    from app.scenes import get_scene
    from core.project_file import load_project, save_project

    doc = get_scene("patch-grid").document()
    doc.maps.write("trample", 2, 3, np.broadcast_to(np.array(brush_value(0.7, 45.0)), (4, 5, 2)))
    path = tmp_path / "trodden.sward"
    save_project(path, doc)
    again = load_project(path)
    assert np.array_equal(again.maps.layer("trample"), doc.maps.layer("trample"))
    # the same project as a file written before trampled grass: five maps in the stack
    old = tmp_path / "old.sward"
    with zipfile.ZipFile(path) as z, zipfile.ZipFile(old, "w") as out:
        for info in z.infolist():
            data = z.read(info)
            if info.filename == "maps.npz":
                stack = np.load(io.BytesIO(data))["stack"][:5]
                buffer = io.BytesIO()
                np.savez_compressed(buffer, stack=stack)
                data = buffer.getvalue()
            out.writestr(info, data)
    older = load_project(old)
    assert not trampled(older.maps.layer("trample"))
    assert np.array_equal(older.maps.layer("density"), doc.maps.layer("density"))


@pytest.mark.parametrize("layers", [4, 7])
def test_a_stack_of_another_number_of_maps_is_refused(tmp_path, layers):
    from app.scenes import get_scene
    from core.project_file import ProjectError, load_project, save_project

    path = tmp_path / "p.sward"
    save_project(path, get_scene("patch-grid").document())
    bad = tmp_path / "bad.sward"
    with zipfile.ZipFile(path) as z, zipfile.ZipFile(bad, "w") as out:
        for info in z.infolist():
            data = z.read(info)
            if info.filename == "maps.npz":
                stack = np.load(io.BytesIO(data))["stack"]
                stack = np.concatenate([stack] * 2)[:layers]
                buffer = io.BytesIO()
                np.savez_compressed(buffer, stack=stack)
                data = buffer.getvalue()
            out.writestr(info, data)
    with pytest.raises(ProjectError, match=r"bad\.sward.*stack must be"):
        load_project(bad)
