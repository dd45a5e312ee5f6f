"""`sward export` as a user runs it: glTF that the Khronos validator passes for every built-in
scene, read back by the library (counts, the patch's vertices, instances per cell with grass),
the design maps bit for bit, the settings, and bad input refused in one line."""

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import OpenEXR
import png
import pygltflib
import pytest
from PIL import Image

from app.scenes import SCENES, get_scene
from core.design_maps import LAYERS
from core.export_grass import grass_cells
from core.map_io import quantized
from core.patch import blade_texture, generate_patch
from tests.test_cli import sward

ROOT = Path(__file__).resolve().parents[1]
VALIDATOR = ROOT / ".venv" / "node" / "node_modules" / "gltf-validator"


def accessor(gltf, data: bytes, index: int, width: int) -> np.ndarray:
    """A glTF accessor's values from the buffer: (count, width), or (count,) for width 1."""
    a = gltf.accessors[index]
    view = gltf.bufferViews[a.bufferView]
    dtype = np.uint32 if a.componentType == 5125 else np.float32
    raw = np.frombuffer(data, dtype, a.count * width, view.byteOffset + a.byteOffset)
    return raw.reshape(a.count, width) if width > 1 else raw


def turned(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Vectors v (n, 3) turned by unit quaternions q (n, 4: x, y, z, w)."""
    u, w = q[:, :3], q[:, 3:]
    t = 2.0 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


def _validate(path: Path) -> dict:
    if shutil.which("node") is None or not VALIDATOR.is_dir():
        pytest.skip("the glTF validator: make test installs node and npm's gltf-validator")
    run = subprocess.run(
        ["node", str(ROOT / "tests" / "tools" / "gltf_validate.js"), str(VALIDATOR), str(path)],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)["issues"]


@pytest.mark.parametrize("scene", sorted(SCENES))
def test_every_scene_exports_glTF_the_khronos_validator_passes(scene, tmp_path):
    out = tmp_path / scene
    r = sward("export", "--scene", scene, "--out", str(out), "--what", "patch,instances,terrain")
    assert r.returncode == 0, r.stderr
    issues = _validate(out / "grass.gltf")
    assert (issues["numErrors"], issues["numWarnings"]) == (0, 0), issues["messages"][:5]


def test_the_meadow_reads_back_as_it_was_designed(tmp_path):
    out = tmp_path / "meadow"
    r = sward("export", "--scene", "meadow", "--out", str(out))
    assert r.returncode == 0, r.stderr
    document = get_scene("meadow").document()
    gltf = pygltflib.GLTF2().load(str(out / "grass.gltf"))
    assert "EXT_mesh_gpu_instancing" in gltf.extensionsUsed
    grows = grass_cells(document)
    data = (out / "grass.bin").read_bytes()

    def read(index: int, width: int) -> np.ndarray:
        return accessor(gltf, data, index, width)

    for index, kind in enumerate(document.grass_types):
        patch = generate_patch(kind.params)
        (holder,) = [n for n in gltf.nodes if n.name == f"grass {kind.name}"]
        blocks = [gltf.nodes[c] for c in holder.children]
        mesh = gltf.meshes[blocks[0].mesh]
        attributes = mesh.primitives[0].attributes
        assert gltf.accessors[attributes.POSITION].count == len(patch.vertices)
        threshold = read(attributes._THRESHOLD, 1)
        assert np.array_equal(threshold, patch.vertices["threshold"])
        assert np.array_equal(read(attributes._ROOT, 2), patch.vertices["root"])
        assert np.array_equal(read(attributes._CURVE1, 3), patch.vertices["ctrl1"])
        assert np.array_equal(read(attributes._CURVE2, 3), patch.vertices["ctrl2"])
        # COLOR_0 is linear: Sward's display-encoded blade colours decoded (sRGB)
        linear = read(attributes.COLOR_0, 3).astype(np.float64)
        display = np.where(linear <= 0.0031308, linear * 12.92, 1.055 * linear ** (1 / 2.4) - 0.055)
        assert np.allclose(display, patch.vertices["color"], atol=1e-5)
        material = gltf.materials[mesh.primitives[0].material]
        assert (material.alphaMode, material.doubleSided) == ("MASK", True)
        blade = gltf.images[
            gltf.textures[material.pbrMetallicRoughness.baseColorTexture.index].source
        ]
        with Image.open(out / blade.uri) as image:  # the texture Sward's blades are drawn with
            assert np.array_equal(np.asarray(image), blade_texture())
        moves = [b.extensions["EXT_mesh_gpu_instancing"]["attributes"] for b in blocks]
        translations = np.concatenate([read(m["TRANSLATION"], 3) for m in moves])
        rotations = np.concatenate([read(m["ROTATION"], 4) for m in moves]).astype(np.float64)
        scales = np.concatenate([read(m["SCALE"], 3) for m in moves])
        # one instance per cell with grass of this type, each on its own cell
        assert 0 < len(translations) == grows[index].sum()
        spec = document.terrain_spec
        centre = translations + turned(rotations, scales * [0.5, 0.0, 0.5])
        ix, iz = np.floor(centre[:, [0, 2]] + [spec.columns / 2, spec.rows / 2]).astype(int).T
        assert grows[index][ix, iz].all() and len(set(zip(ix, iz, strict=True))) == len(ix)
        assert set(np.unique(scales[:, [0, 2]])) == {-1.0, 1.0}  # the tiling's mirror bits
        # each cell's centre lies on the ground, on the meadow's hills, the cell tilted to the
        # ground's slope: its corners near the ground too (no steps between cells)
        assert np.allclose(np.linalg.norm(rotations, axis=1), 1.0, atol=1e-5)
        ground = [document.ground_at(x, z) for x, z in centre[:50, [0, 2]]]
        assert np.allclose(centre[:50, 1], ground, atol=1e-4) and np.std(ground) > 0.1
        corner = translations + turned(rotations, scales * [1.0, 0.0, 1.0])  # tilted
        tilted = np.abs(corner[:, 1] - [document.ground_at(x, z) for x, z in corner[:, [0, 2]]])
        upright = centre[:, [0, 2]] + 0.5 * scales[:, [0, 2]]  # the same corner, level
        level = np.abs(centre[:, 1] - [document.ground_at(x, z) for x, z in upright])
        assert tilted.mean() < 0.5 * level.mean()
    # the tall grass grows in clumps: not on every cell
    assert grows[1].sum() < grows[1].size

    for layer in LAYERS:
        values = document.maps.layer(layer.name)[..., : layer.channels]
        with (out / "maps" / f"{layer.name}.png").open("rb") as f:
            w, h, rows, info = png.Reader(file=f).read()
            pixels = np.vstack([np.asarray(row, np.uint16) for row in rows])
        assert info["bitdepth"] == 16 and (w, h) == document.maps.size
        if layer.channels == 2:  # the trample map: a flow map, RG and blue 0
            values = np.concatenate([values, np.zeros_like(values[..., :1])], axis=2)
        assert np.array_equal(pixels.reshape(values.shape), quantized(values)), layer.name
        with OpenEXR.File(str(out / "maps" / f"{layer.name}.exr")) as exr:
            stored = next(iter(exr.channels().values())).pixels
        assert np.array_equal(np.asarray(stored).reshape(values.shape), values), layer.name
    r16 = np.fromfile(out / "maps" / "height.r16", "<u2").reshape(document.maps.size[::-1])
    assert np.array_equal(r16, quantized(document.maps.layer("height")[..., 0]))

    settings = json.loads((out / "settings.json").read_text())
    assert [g["name"] for g in settings["grass"]] == document.grass_names
    assert settings["grass"][0]["lod"][0]["representation"] == "geometry"


@pytest.mark.parametrize(
    "args,words",
    [
        (("--what", "patch,trees"), "trees is not one of"),
        (("--format", "fbx"), "invalid choice: 'fbx'"),
    ],
)
def test_export_refuses_bad_input_in_one_line(tmp_path, args, words):
    r = sward("export", "--scene", "patch-grid", "--out", str(tmp_path / "x"), *args)
    assert r.returncode == 2 and words in r.stderr and "Traceback" not in r.stderr


def test_an_export_into_a_file_not_a_folder_is_refused(tmp_path):
    taken = tmp_path / "taken"
    taken.write_text("mine")
    r = sward("export", "--scene", "patch-grid", "--out", str(taken))
    assert r.returncode == 2 and "not a folder" in r.stderr
    assert taken.read_text() == "mine"


def test_usd_lists_each_types_patch_and_its_instances(tmp_path):
    pytest.importorskip("pxr", reason="the optional extra sward[usd]; make test installs it")
    from pxr import Usd, UsdGeom

    out = tmp_path / "usd"
    r = sward("export", "--scene", "meadow", "--format", "usd", "--out", str(out))
    assert r.returncode == 0, r.stderr
    document = get_scene("meadow").document()
    stage = Usd.Stage.Open(str(out / "grass.usda"))  # every payload loaded
    assert UsdGeom.GetStageUpAxis(stage) == "Y"
    for index, kind in enumerate(document.grass_types):
        holder = stage.GetPrimAtPath(f"/World/{kind.name.replace(' ', '_')}")
        instancers = [UsdGeom.PointInstancer(p) for p in holder.GetChildren()]
        assert instancers and all(i for i in instancers)
        count = sum(len(i.GetProtoIndicesAttr().Get()) for i in instancers)
        assert count == grass_cells(document)[index].sum()
        (target,) = instancers[0].GetPrototypesRel().GetTargets()
        patch = UsdGeom.Mesh(stage.GetPrimAtPath(target))
        assert len(patch.GetPointsAttr().Get()) == len(generate_patch(kind.params).vertices)
        assert UsdGeom.PrimvarsAPI(patch).GetPrimvar("threshold").GetInterpolation() == "vertex"
        curve = np.array(UsdGeom.PrimvarsAPI(patch).GetPrimvar("curve2").Get())
        assert np.array_equal(curve, generate_patch(kind.params).vertices["ctrl2"])
    terrain = UsdGeom.Mesh(stage.GetPrimAtPath("/World/Terrain"))
    assert len(terrain.GetPointsAttr().Get()) == (document.terrain_spec.columns + 1) ** 2


def test_usd_without_usd_core_says_what_to_install(tmp_path, monkeypatch):
    import sys

    from app.export import ExportError, export

    monkeypatch.setitem(sys.modules, "pxr", None)  # as where usd-core is not installed
    with pytest.raises(ExportError, match=r"pip install 'sward\[usd\]'"):
        export(get_scene("patch-grid").document(), tmp_path, ("patch",), format="usd")


def test_slices_are_atlases_of_every_mip_level_with_their_layout(tmp_path):
    from app.export_slices import slice_counts

    out = tmp_path / "slices"
    r = sward("export", "--scene", "meadow", "--out", str(out), "--what", "slices")
    assert r.returncode == 0, r.stderr
    document = get_scene("meadow").document()
    sp = document.slices
    for kind in document.grass_types:
        for n in slice_counts(document, kind):
            folder = out / "slices" / f"{kind.name.replace(' ', '-')}-{n}"
            layout = json.loads((folder / "layout.json").read_text())
            assert layout["slices"] == n and layout["patch_height"] > 0
            for family, count in (("x", n), ("z", n), ("top", 1)):
                levels = layout["families"][family]["levels"]
                assert layout["families"][family]["count"] == count
                w0, h0 = (sp.top, sp.top) if family == "top" else (sp.width, sp.height * n)
                assert levels[0]["size"] == [w0, h0]
                for level in levels:  # each level half the one before, down to one texel row
                    k = level["level"]
                    with Image.open(folder / level["color"]) as color:
                        assert (
                            color.size == (max(w0 >> k, 1), max(h0 >> k, 1))
                            and color.mode == "RGBA"
                        )
                        alpha = np.asarray(color)[..., 3]
                    with (folder / level["data"]).open("rb") as f:
                        w, h, rows, info = png.Reader(file=f).read()
                        data = np.vstack([np.asarray(row, np.uint16) for row in rows]).reshape(
                            h, w, 4
                        )
                    assert info["bitdepth"] == 16 and (w, h) == color.size
                    if k == 0:  # grass where the colour has alpha, and there a threshold
                        assert 0.2 < (alpha > 0).mean() and (data[..., 3][alpha > 128] > 0).all()
