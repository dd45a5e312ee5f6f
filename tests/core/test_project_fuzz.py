"""Malformed project files: every variant of a valid project — truncated, bit-flipped, each
field given wrong types and extreme values, zip and npz structure tricks, files that are not
regular — is refused with one line naming the file, or loads as a valid document. Never a
traceback, never an unbounded read (a sample runs here; sizes are kept small)."""

import dataclasses
import io
import json
import os
import random
import zipfile

import numpy as np
import pytest

from app.scenes import get_scene
from core.document import Document
from core.project_file import ProjectError, load_project, save_project
from tests.project_files import leaves, project_parts, replaced
from tests.project_files import write_project as write

BAD_VALUES = ["text", [], {}, None, True, -1, 0, 1e308, 10**12, -1e9, [1, 2, 3, 4, 5]]


@pytest.fixture(scope="module")
def good(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fuzz")
    scene = get_scene("meadow")
    scene = dataclasses.replace(scene, params=scene.params.replace(blade_count=50))
    scene = dataclasses.replace(scene, map_size=(16, 16))
    path = folder / "good.sward"
    save_project(path, scene.document())
    return (path.read_bytes(), *project_parts(path))


def outcome(path):
    """'refused' (one line naming the file) or 'loaded' (a document that holds together)."""
    try:
        doc = load_project(path)
    except ProjectError as exc:
        text = str(exc)
        assert str(path) in text and "\n" not in text, text
        return "refused"
    assert isinstance(doc, Document)
    doc.terrain  # noqa: B018 - the quadtree builds
    doc.camera()
    doc.prop_boxes()
    return "loaded"


def test_truncated_and_bit_flipped_files_are_refused_or_load(good, tmp_path):
    raw = good[0]
    rng = random.Random(7)
    seen = set()
    for i, cut in enumerate(sorted(rng.sample(range(1, len(raw)), 25))):
        (tmp_path / f"cut{i}.sward").write_bytes(raw[:cut])
        assert outcome(tmp_path / f"cut{i}.sward") == "refused"
    for i in range(60):
        flipped = bytearray(raw)
        at = rng.randrange(len(raw))
        flipped[at] ^= 1 << rng.randrange(8)
        (tmp_path / f"flip{i}.sward").write_bytes(bytes(flipped))
        seen.add(outcome(tmp_path / f"flip{i}.sward"))
    assert "refused" in seen


def test_every_field_with_wrong_types_and_extreme_values(good, tmp_path):
    _, data, maps = good
    rng = random.Random(3)
    places = list(leaves(data))
    results = {"refused": 0, "loaded": 0}
    for n, where in enumerate(rng.sample(places, min(len(places), 70))):
        for m, value in enumerate(rng.sample(BAD_VALUES, 4)):
            path = tmp_path / f"f{n}_{m}.sward"
            write(path, replaced(data, where, value), maps)
            results[outcome(path)] += 1
    assert results["refused"] > 200


@pytest.mark.parametrize(
    ("where", "value", "words"),
    [
        (("terrain", "columns"), 0, "terrain.columns"),
        (("terrain", "columns"), 100000, "terrain.columns"),
        (("terrain",), {"columns": 5000, "rows": 5000, "height_scale": 1.0}, "cells"),
        (("terrain", "mirror_seed"), "x", "terrain.mirror_seed"),
        (("terrain", "height_scale"), 1e6, "terrain.height_scale"),
        (("lod", "levels", 1, "slices"), 10**12, "lod.levels[1].slices"),
        (("lod", "levels", 1, "slices"), 0, "lod.levels[1].slices"),
        (("density",), -1, "density"),
        (("density",), 5, "density"),
        (("fog_distance",), 0, "fog_distance"),
        (("cameras",), 7, "cameras"),
        (("default_camera",), "nowhere", "default_camera"),
        (("params", "clustered"), "yes", "params.clustered"),
        (("params", "blade_count"), 1e400, "malformed"),  # Infinity is not JSON
        (("name",), ["a", "list"], "name"),
        (("light", "sun_azimuth"), 1e9, "light.sun_azimuth"),
        (("lod", "segment_tolerance"), 9, "lod.segment_tolerance"),
        (("paint_rule", "slope"), [30, 10], "paint_rule.slope: the least first"),
        (("paint_rule", "slope"), [0, 95], "paint_rule.slope"),
        (("species", "soil", "exponent"), 0, "species.soil.exponent"),
        (("species", "soil", "weights"), [0, 0, 0], "weights cannot all be 0"),
        (("species", "soil", "reference"), [0.5, 2, 0], "species.soil.reference"),
        (("species", "kinds"), [{}, {}, {}], "species.kinds has 3 rules for 2 grass types"),
    ],
)
def test_wrong_values_are_refused_naming_the_field(good, tmp_path, where, value, words):
    _, data, maps = good
    path = tmp_path / "bad.sward"
    write(path, replaced(data, where, value), maps)
    with pytest.raises(ProjectError) as info:
        load_project(path)
    assert str(path) in str(info.value) and words in str(info.value)


def test_camera_relations_props_and_non_numbers(good, tmp_path):
    _, data, maps = good
    name = data["default_camera"]
    camera = data["cameras"][name]
    cases = {
        "eye and target must differ": replaced(data, ("cameras", name, "eye"), camera["target"]),
        "must be less than far": replaced(data, ("cameras", name, "near"), 1e6),
        "props": replaced(data, ("props",), [[[0, 0], [1, 1, 1], [1, 1, 1]]] * 90000),
        "props[0]": replaced(data, ("props",), [[[0, 0], [0, 1, 1], [1, 1, 1]]]),
        "props[0][4]: invalid enum value 'pebble'": replaced(
            data, ("props",), [[[0, 0], [1, 1, 1], [1, 1, 1], 0, "pebble"]]
        ),
        "props[1] must be": replaced(
            data,
            ("props",),
            [[[0, 0], [1, 1, 1], [1, 1, 1]], [[0, 0], [1, 1, 1], [1, 1, 1], "rock"]],
        ),
    }
    for words, variant in cases.items():
        path = tmp_path / "c.sward"
        write(path, variant, maps)
        with pytest.raises(ProjectError, match=words.replace("[", r"\[")):
            load_project(path)
    text = json.dumps(data).replace('"density": 1.0', '"density": NaN')
    with zipfile.ZipFile(tmp_path / "nan.sward", "w") as z:
        z.writestr("project.json", text)
        z.writestr("maps.npz", maps)
    with pytest.raises(ProjectError, match="malformed"):
        load_project(tmp_path / "nan.sward")


def npz(array) -> bytes:
    buffer = io.BytesIO()
    np.savez_compressed(buffer, stack=array)
    return buffer.getvalue()


def test_zip_and_npz_tricks_are_refused_before_reading_much(good, tmp_path):
    _, data, maps = good
    huge = io.BytesIO()  # a .npy header claiming 200 GB, with no data behind it
    np.lib.format.write_array_header_1_0(
        huge, {"descr": "<f4", "fortran_order": False, "shape": (5, 100000, 100000, 4)}
    )
    with zipfile.ZipFile(inner := io.BytesIO(), "w") as z:
        z.writestr("stack.npy", huge.getvalue())
    plain = io.BytesIO()
    np.save(plain, np.ones((5, 4, 4, 4), np.float32))
    cases = {
        "huge header": ({}, inner.getvalue(), "rows and columns"),
        "plain npy": ({}, plain.getvalue(), "not an npz"),
        "complex maps": ({}, npz(np.ones((5, 4, 4, 4), np.complex64)), "float32"),
        "big values": ({}, npz(np.full((5, 4, 4, 4), 1e30, np.float32)), "density map"),
        "negative": ({}, npz(-np.ones((5, 4, 4, 4), np.float32)), "0 … 1"),
        "bzip2": ({"compression": zipfile.ZIP_BZIP2}, maps, "unsupported compression"),
    }
    for name, (kwargs, stack, words) in cases.items():
        path = tmp_path / f"{name}.sward"
        write(path, data, stack, **kwargs)
        with pytest.raises(ProjectError, match=words):
            load_project(path)
    bomb = tmp_path / "bomb.sward"
    with zipfile.ZipFile(bomb, "w", compression=zipfile.ZIP_DEFLATED) as z:
        z.writestr("project.json", b" " * (40 << 20))  # 40 MB of spaces: about 40 KB packed
        z.writestr("maps.npz", maps)
    assert bomb.stat().st_size < 1 << 20
    with pytest.raises(ProjectError, match="would inflate"):
        load_project(bomb)
    deep = tmp_path / "deep.sward"
    with zipfile.ZipFile(deep, "w") as z:
        z.writestr("project.json", "[" * 100000 + "]" * 100000)
        z.writestr("maps.npz", maps)
    with pytest.raises(ProjectError):
        load_project(deep)


def test_an_encrypted_member_is_refused_before_reading(good, tmp_path):
    raw = bytearray(good[0])
    with zipfile.ZipFile(io.BytesIO(good[0])) as z:
        at = z.start_dir  # the central directory; its first entry is project.json's
    assert raw[at : at + 4] == b"PK\x01\x02"
    raw[at + 8] |= 0x01  # its "encrypted" flag
    path = tmp_path / "locked.sward"
    path.write_bytes(bytes(raw))
    with pytest.raises(ProjectError, match=r"project\.json is encrypted"):
        load_project(path)


def test_only_regular_files_are_read(tmp_path):
    fifo = tmp_path / "pipe.sward"
    os.mkfifo(fifo)
    link = tmp_path / "random.sward"
    link.symlink_to("/dev/urandom")
    folder = tmp_path / "folder.sward"
    folder.mkdir()
    for path in (fifo, link, folder):
        with pytest.raises(ProjectError, match="not a regular file"):
            load_project(path)
