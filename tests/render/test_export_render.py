"""The meadow drawn from its exported glTF by Sward's own geometry renderer matches
`sward render --only geometry` of the same camera within the blade-detail floor of `sward
quality`: the patch comes from the file's mesh (positions, normals, UV, colours, roots,
thresholds, curves) and its parameters from settings.json, the instances (which cells, their mirror
bits) from EXT_mesh_gpu_instancing. A mesh attribute or a placement lost on the way shows here
as a picture that differs."""

import dataclasses
import json

import numpy as np
import pygltflib

from app.export import export
from app.quality import shifted
from app.scenes import get_scene
from core.grid import INSTANCE_DTYPE
from core.image_diff import QUARTER, flip
from core.params import PatchParams
from core.patch import VERTEX_DTYPE, GrassPatch
from core.segments import chord_colors
from tests.test_export import accessor, turned

SIZE = (480, 270)


def _from_export(folder, document):
    """Per grass type: the patch and the instances as the exported files hold them."""
    gltf = pygltflib.GLTF2().load(str(folder / "grass.gltf"))
    data = (folder / "grass.bin").read_bytes()
    settings = json.loads((folder / "settings.json").read_text())
    found = []
    for saved in settings["grass"]:
        params = PatchParams.from_dict(saved["params"])
        (holder,) = [n for n in gltf.nodes if n.name == f"grass {saved['name']}"]
        blocks = [gltf.nodes[c] for c in holder.children]
        primitive = gltf.meshes[blocks[0].mesh].primitives[0]
        a = primitive.attributes
        vertices = np.zeros(gltf.accessors[a.POSITION].count, VERTEX_DTYPE)
        vertices["position"] = accessor(gltf, data, a.POSITION, 3)
        vertices["normal"] = accessor(gltf, data, a.NORMAL, 3)
        vertices["uv"] = accessor(gltf, data, a.TEXCOORD_0, 2)
        linear = accessor(gltf, data, a.COLOR_0, 3).astype(np.float64)  # as Sward shows them:
        vertices["color"] = np.where(  # encoded for the display (sRGB), as an engine does
            linear <= 0.0031308, linear * 12.92, 1.055 * linear ** (1 / 2.4) - 0.055
        )
        vertices["root"] = accessor(gltf, data, a._ROOT, 2)
        vertices["threshold"] = accessor(gltf, data, a._THRESHOLD, 1)
        vertices["ctrl1"] = accessor(gltf, data, a._CURVE1, 3)
        vertices["ctrl2"] = accessor(gltf, data, a._CURVE2, 3)
        per_blade = (params.subdivisions + 1) * 2
        rows = vertices["color"].reshape(-1, params.subdivisions + 1, 2, 3)[:, :, 0]
        # the colours fewer segments slide onto follow from the file's (core/segments.py)
        vertices["chord_color"] = np.repeat(chord_colors(rows), 2, axis=1).reshape(-1, 3)
        patch = GrassPatch(
            params,
            vertices,
            accessor(gltf, data, primitive.indices, 1).copy(),
            vertices["root"][::per_blade].copy(),
            vertices["threshold"][::per_blade].copy(),
            float(vertices["position"][:, 1].max()),
        )
        moves = [b.extensions["EXT_mesh_gpu_instancing"]["attributes"] for b in blocks]
        t = np.concatenate([accessor(gltf, data, m["TRANSLATION"], 3) for m in moves])
        q = np.concatenate([accessor(gltf, data, m["ROTATION"], 4) for m in moves]).astype(float)
        s = np.concatenate([accessor(gltf, data, m["SCALE"], 3) for m in moves])
        spec = document.terrain_spec
        centre = t + turned(q, s * [0.5, 0.0, 0.5])  # the cell's centre, wherever it is tilted
        ix, iz = np.floor(centre[:, [0, 2]] + [spec.columns / 2, spec.rows / 2]).astype(int).T
        instances = document.terrain.cells(ix, iz)  # the cells' map transforms and ground
        instances["mirror"] = s[:, [0, 2]]  # the file's mirror bits, not the terrain's
        found.append((patch, instances))
    return found


def test_the_meadow_drawn_from_its_export_matches_all_geometry(headless, tmp_path):
    document = get_scene("meadow").document()
    export(document, tmp_path, ("patch", "instances", "lod"))
    # the nearest 900 cells (two grass types, mirror bits, hills): every instance of the file
    # drawn where it stands; the whole meadow as blades took a minute a frame on llvmpipe
    camera = dataclasses.replace(document.camera(), far=18.0)
    renderer = headless(document, mode="geometry")
    renderer.pipeline.segment_lod = False  # the file holds whole strips: an engine's LOD is its own
    direct, _ = renderer.render(camera, SIZE, measure=False)
    floor_image, _ = renderer.render(
        shifted(camera, document.params(0).width_max), SIZE, measure=False
    )
    floor, _ = flip(direct, floor_image, QUARTER)

    loaded = _from_export(tmp_path, document)
    pipeline = renderer.pipeline
    for grass, (patch, instances) in zip(pipeline.grass_types, loaded, strict=True):
        grass.geometry.set_patch(patch)

        def upload(cells, *args, grass=grass, instances=instances, **kwargs):
            assert set(cells.batches) <= {("geometry", 0)}  # all geometry, as --only geometry
            grass.geometry.set_instances(instances)
            return {("geometry", 0): (grass.geometry, int(instances.size))}

        grass.upload = upload
    assert loaded[0][1].dtype == INSTANCE_DTYPE and all(i.size for _, i in loaded)
    from_file, _ = renderer.render(camera, SIZE, measure=False)
    difference, _ = flip(direct, from_file, QUARTER)
    # within the floor of two frames a blade apart; without the file's mirror bits it is not
    assert difference <= floor, (difference, floor)
