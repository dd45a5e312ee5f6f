"""`sward export`: a design as files other tools read (docs/export.md says what each holds).

    DIR/grass.gltf + grass.bin   glTF 2.0 (pygltflib): each grass type's patch as a mesh, its
                                 instances over the terrain through EXT_mesh_gpu_instancing in
                                 blocks of cells, the terrain as a mesh with the colour map on it
    DIR/slices/                  each grass type's slices as PNG atlases (app/export_slices.py)
    DIR/maps/                    the design maps: 16-bit PNG, OpenEXR (float), r16 (one channel)
    DIR/settings.json            grass types (patch parameters, LOD levels), light, terrain

The binary buffer is written block by block as the instances are made, so a large terrain
needs memory for one block, not for the whole export."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path

import numpy as np

from core.export_grass import block_instances, blocks, grass_cells, ground_mesh, patch_mesh
from core.patch import blade_texture, generate_patch

WHAT = ("patch", "slices", "instances", "terrain", "maps", "lod")
GROUND_VERTICES = 513  # the terrain mesh's vertices along its longer side, at most
FLOAT, UINT = 5126, 5125  # glTF component types
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963


class ExportError(Exception):
    """An export that cannot be written; the message names the file and the reason."""


class _Buffer:
    """The .bin file, written as it grows; each view starts on a 4-byte boundary."""

    def __init__(self, path: Path) -> None:
        self.path, self.file, self.length = path, path.open("wb"), 0

    def add(self, data: np.ndarray) -> tuple[int, int]:
        raw = np.ascontiguousarray(data).tobytes()
        offset = self.length
        self.file.write(raw)
        pad = (-len(raw)) % 4
        self.file.write(b"\0" * pad)
        self.length += len(raw) + pad
        return offset, len(raw)

    def close(self) -> None:
        self.file.close()


class _Gltf:
    """The glTF document being built (pygltflib) and its buffer."""

    def __init__(self, folder: Path) -> None:
        import pygltflib as g

        self.g = g
        self.doc = g.GLTF2(asset=g.Asset(generator="Sward", version="2.0"))
        self.doc.scenes = [g.Scene(nodes=[])]
        self.doc.scene = 0
        self.folder = folder
        self.buffer = _Buffer(folder / "grass.bin")

    def accessor(self, data: np.ndarray, kind: str, target: int | None = None, bounds=False) -> int:
        g = self.g
        offset, length = self.buffer.add(data)
        self.doc.bufferViews.append(
            g.BufferView(buffer=0, byteOffset=offset, byteLength=length, target=target)
        )
        flat = data.reshape(data.shape[0], -1)
        accessor = g.Accessor(
            bufferView=len(self.doc.bufferViews) - 1,
            componentType=UINT if data.dtype == np.uint32 else FLOAT,
            count=int(data.shape[0]),
            type=kind,
        )
        if bounds:
            accessor.min = [float(v) for v in flat.min(axis=0)]
            accessor.max = [float(v) for v in flat.max(axis=0)]
        self.doc.accessors.append(accessor)
        return len(self.doc.accessors) - 1

    def node(self, node, parent: int | None) -> int:
        self.doc.nodes.append(node)
        index = len(self.doc.nodes) - 1
        if parent is None:
            self.doc.scenes[0].nodes.append(index)
        else:
            self.doc.nodes[parent].children.append(index)
        return index

    def finish(self, path: Path) -> None:
        self.buffer.close()
        self.doc.buffers = [self.g.Buffer(uri=self.buffer.path.name, byteLength=self.buffer.length)]
        path.write_text(self.doc.to_json(indent=1) + "\n")


def export(
    document,
    out: Path,
    what: tuple[str, ...] = WHAT,
    say: Callable[[str], None] = lambda _text: None,
    format: str = "gltf",
) -> dict:
    """Write the export into `out` (made if missing); what was written, with counts. The
    meshes and instances go to glTF or, with format="usd", to USD (app/export_usd.py)."""
    out.mkdir(parents=True, exist_ok=True)
    written: dict = {"folder": str(out), "what": list(what), "format": format}
    try:
        if {"patch", "instances", "terrain"} & set(what):
            if format == "usd":
                from app.export_usd import UsdMissing, export_usd

                try:
                    written["usd"] = export_usd(document, out, what, say)
                except UsdMissing as exc:
                    raise ExportError(str(exc)) from None
            else:
                written["gltf"] = _gltf(document, out, what, say)
        if "slices" in what:
            from app.export_slices import export_slices

            written["slices"] = export_slices(document, out, say)
        if "maps" in what:
            written["maps"] = _maps(document, out / "maps", say)
        if "lod" in what:
            (out / "settings.json").write_text(json.dumps(settings(document), indent=2) + "\n")
            written["settings"] = "settings.json"
    except OSError as exc:
        raise ExportError(f"{exc.filename or out}: cannot write ({exc.strerror or exc})") from None
    return written


def _gltf(document, out: Path, what: tuple[str, ...], say) -> dict:
    import pygltflib as g

    gltf = _Gltf(out)
    counts: dict = {"instances": {}, "vertices": {}, "blocks": 0}
    root = gltf.node(g.Node(name=document.name or "sward"), None)
    grows = grass_cells(document) if "instances" in what else []
    heights = document.heights()
    for index, kind in enumerate(document.grass_types):
        if "patch" not in what and "instances" not in what:
            break
        mesh = _patch_mesh(gltf, kind)
        counts["vertices"][kind.name] = gltf.doc.accessors[
            gltf.doc.meshes[mesh].primitives[0].attributes.POSITION
        ].count
        holder = gltf.node(g.Node(name=f"grass {kind.name}"), root)
        if "instances" not in what:  # the patch alone, at the origin
            gltf.doc.nodes[holder].mesh = mesh
            continue
        total = 0
        spec = document.terrain_spec
        every = list(blocks(spec.columns, spec.rows))
        for done, block in enumerate(every, 1):
            if done % max(1, len(every) // 20) == 0:
                say(f"{kind.name}: blocks {done}/{len(every)}")
            translation, rotation, scale = block_instances(document, grows[index], block, heights)
            if translation.shape[0] == 0:
                continue
            instancing = {
                "attributes": {
                    "TRANSLATION": gltf.accessor(translation, "VEC3"),
                    "ROTATION": gltf.accessor(rotation, "VEC4"),
                    "SCALE": gltf.accessor(scale, "VEC3"),
                }
            }
            gltf.node(
                g.Node(
                    name=f"{kind.name} cells {block[0]},{block[1]}",
                    mesh=mesh,
                    extensions={"EXT_mesh_gpu_instancing": instancing},
                ),
                holder,
            )
            total += translation.shape[0]
            counts["blocks"] += 1
        counts["instances"][kind.name] = total
        say(f"{kind.name}: {total} instances")
    if counts["blocks"]:
        gltf.doc.extensionsUsed = ["EXT_mesh_gpu_instancing"]
    if "terrain" in what:
        counts["ground_vertices"] = _ground(gltf, document, out, root)
    gltf.finish(out / "grass.gltf")
    counts["bytes"] = gltf.buffer.length
    return counts


def _patch_mesh(gltf: _Gltf, kind) -> int:
    from render.geometry import GeometryRenderer

    g = gltf.g
    m = patch_mesh(generate_patch(kind.params))
    attributes = g.Attributes(
        POSITION=gltf.accessor(m["position"], "VEC3", ARRAY_BUFFER, bounds=True),
        NORMAL=gltf.accessor(m["normal"], "VEC3", ARRAY_BUFFER),
        COLOR_0=gltf.accessor(m["color"], "VEC3", ARRAY_BUFFER),
        TEXCOORD_0=gltf.accessor(m["uv"], "VEC2", ARRAY_BUFFER),
    )
    # each vertex's blade: its density threshold and root, application-specific attributes
    attributes._THRESHOLD = gltf.accessor(m["threshold"], "SCALAR", ARRAY_BUFFER)
    attributes._ROOT = gltf.accessor(m["root"], "VEC2", ARRAY_BUFFER)
    # its curve from the root (quadratic Bézier control points): for bending and segment LOD
    attributes._CURVE1 = gltf.accessor(m["ctrl1"], "VEC3", ARRAY_BUFFER)
    attributes._CURVE2 = gltf.accessor(m["ctrl2"], "VEC3", ARRAY_BUFFER)
    gltf.doc.materials.append(
        g.Material(
            name=f"grass {kind.name}",
            doubleSided=True,  # a blade is one quad strip seen from both sides
            alphaMode="MASK",  # the blade texture's alpha narrows it to a pointed tip
            alphaCutoff=GeometryRenderer.alpha_ref,  # Sward's own alpha test
            pbrMetallicRoughness=g.PbrMetallicRoughness(
                baseColorTexture=g.TextureInfo(index=_blade_texture(gltf)),
                metallicFactor=0.0,
                roughnessFactor=0.9,
            ),
        )
    )
    primitive = g.Primitive(
        attributes=attributes,
        indices=gltf.accessor(m["indices"], "SCALAR", ELEMENT_ARRAY_BUFFER),
        material=len(gltf.doc.materials) - 1,
    )
    gltf.doc.meshes.append(g.Mesh(name=f"patch {kind.name}", primitives=[primitive]))
    return len(gltf.doc.meshes) - 1


def _blade_texture(gltf: _Gltf) -> int:
    """The blade texture (maps/blade.png, the one Sward's geometry draws with: row 0 the root,
    as glTF's v = 0), written once per export."""
    from PIL import Image

    g = gltf.g
    for i, texture in enumerate(gltf.doc.textures):
        if gltf.doc.images[texture.source].uri == "maps/blade.png":
            return i
    (gltf.folder / "maps").mkdir(exist_ok=True)
    Image.fromarray(blade_texture()).save(gltf.folder / "maps" / "blade.png", format="PNG")
    gltf.doc.images.append(g.Image(uri="maps/blade.png"))
    gltf.doc.samplers.append(g.Sampler(magFilter=9729, minFilter=9987, wrapS=33071, wrapT=33071))
    gltf.doc.textures.append(
        g.Texture(source=len(gltf.doc.images) - 1, sampler=len(gltf.doc.samplers) - 1)
    )
    return len(gltf.doc.textures) - 1


def _ground(gltf: _Gltf, document, out: Path, root: int) -> int:
    """The terrain mesh, textured with the colour map (maps/ground.png, 8-bit RGB)."""
    from PIL import Image

    g = gltf.g
    spec = document.terrain_spec
    step = max(1, math.ceil(max(spec.columns, spec.rows) / (GROUND_VERTICES - 1)))
    m = ground_mesh(document, step)
    color = document.maps.layer("color")[..., :3]
    (out / "maps").mkdir(exist_ok=True)
    Image.fromarray(np.round(np.clip(color, 0, 1) * 255).astype(np.uint8)).save(
        out / "maps" / "ground.png", format="PNG"
    )
    gltf.doc.images.append(g.Image(uri="maps/ground.png"))
    gltf.doc.samplers.append(g.Sampler(magFilter=9729, minFilter=9987, wrapS=33071, wrapT=33071))
    gltf.doc.textures.append(
        g.Texture(source=len(gltf.doc.images) - 1, sampler=len(gltf.doc.samplers) - 1)
    )
    gltf.doc.materials.append(
        g.Material(
            name="ground",
            pbrMetallicRoughness=g.PbrMetallicRoughness(
                baseColorTexture=g.TextureInfo(index=len(gltf.doc.textures) - 1),
                metallicFactor=0.0,
                roughnessFactor=1.0,
            ),
        )
    )
    primitive = g.Primitive(
        attributes=g.Attributes(
            POSITION=gltf.accessor(m["position"], "VEC3", ARRAY_BUFFER, bounds=True),
            NORMAL=gltf.accessor(m["normal"], "VEC3", ARRAY_BUFFER),
            TEXCOORD_0=gltf.accessor(m["uv"], "VEC2", ARRAY_BUFFER),
        ),
        indices=gltf.accessor(m["indices"], "SCALAR", ELEMENT_ARRAY_BUFFER),
        material=len(gltf.doc.materials) - 1,
    )
    gltf.doc.meshes.append(g.Mesh(name="terrain", primitives=[primitive]))
    gltf.node(g.Node(name="terrain", mesh=len(gltf.doc.meshes) - 1), root)
    return int(m["position"].shape[0])


def _maps(document, folder: Path, say) -> list[str]:
    """Each design map as 16-bit PNG and OpenEXR; the height and each grass type's density as
    r16 (raw little-endian 16-bit, the terrain tools' format)."""
    from core.design_maps import LAYERS
    from core.map_io import write_map

    folder.mkdir(parents=True, exist_ok=True)
    names = []
    for layer in LAYERS:
        values = document.maps.layer(layer.name)[..., : layer.channels]
        if layer.channels == 2:  # the trample map as a flow map: RG, blue 0 (a PNG's two
            values = np.concatenate([values, np.zeros_like(values[..., :1])], axis=2)  # are LA)
        png16(folder / f"{layer.name}.png", values)
        _exr(folder / f"{layer.name}.exr", values)
        names += [f"{layer.name}.png", f"{layer.name}.exr"]
    heights = document.maps.layer("height")[..., :1]
    write_map(folder / "height.r16", heights)
    names.append("height.r16")
    density = document.maps.layer("density")
    for kind in document.grass_types:
        name = f"density-{file_name(kind.name)}.r16"
        write_map(folder / name, density[..., kind.channel : kind.channel + 1])
        names.append(name)
    say(f"maps: {len(names)} files")
    return names


def png16(path: Path, values: np.ndarray) -> None:
    import png  # pypng: Pillow writes 16 bits only for one channel

    from core.map_io import quantized

    rows, columns, channels = values.shape
    data = quantized(values).reshape(rows, columns * channels)
    writer = png.Writer(
        columns, rows, greyscale=channels == 1, alpha=channels in (2, 4), bitdepth=16,
        compression=6,
    )  # fmt: skip
    with path.open("wb") as f:
        writer.write(f, data)


def _exr(path: Path, values: np.ndarray) -> None:
    import OpenEXR

    channels = values.shape[2]
    data = np.ascontiguousarray(values, np.float32)
    if channels == 1:
        layers = {"Y": data[..., 0].copy()}
    else:
        layers = {"RGBA"[:channels] if channels in (3, 4) else "RG": data}
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    with OpenEXR.File(header, layers) as f:
        f.write(str(path))


def file_name(name: str) -> str:
    safe = "".join(c if c.isalnum() or c in "-_" else "-" for c in name).strip("-")
    return safe or "grass"


def settings(document) -> dict:
    """Every grass type (density-map channel, patch parameters, LOD levels), the light, the
    terrain, the global density, the slices' parameters and the wind (docs/export.md)."""
    from core.project_file import document_data

    data = document_data(document)
    grass = [
        {
            "name": kind.name,
            "channel": kind.channel,
            "params": kind.params.to_dict(),
            "lod": [
                {
                    "representation": lv.representation,
                    "begin": lv.begin,
                    "end": lv.end,  # None: to the horizon
                    "slices": lv.slices,
                    "macro": lv.macro,
                }
                for lv in kind.lod.levels
            ],
        }
        for kind in document.grass_types
    ]
    return {
        "format": "sward-export-settings",
        "version": 1,
        "name": document.name,
        "grass": grass,
        **{k: data[k] for k in ("density", "terrain", "light", "slices", "wind")},
    }
