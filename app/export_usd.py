"""`sward export --format usd`: the design as USD (usd-core, the optional extra `sward[usd]`).

    DIR/grass.usda                 the stage: /World/Terrain and per grass type /World/<type>,
                                   whose blocks of cells are payloads
    DIR/usd/patch-<type>.usdc      the patch mesh (points, normals, displayColor, st and the
                                   blades' density thresholds as primvars)
    DIR/usd/<type>-<x>-<z>.usdc    one block's UsdGeom.PointInstancer of that patch
    DIR/usd/terrain.usdc           the terrain mesh

Each block is written and released before the next, so a large terrain needs memory for one
block; an application loads the payloads it wants (all of them by default)."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np

from core.export_grass import block_instances, blocks, grass_cells, ground_mesh, patch_mesh
from core.patch import generate_patch


class UsdMissing(Exception):
    """usd-core is not installed."""


def _pxr():
    try:
        from pxr import Gf, Sdf, Usd, UsdGeom, Vt
    except ImportError:
        raise UsdMissing(
            "--format usd needs usd-core: pip install 'sward[usd]' (or pip install usd-core)"
        ) from None
    return Gf, Sdf, Usd, UsdGeom, Vt


def export_usd(document, out: Path, what: tuple[str, ...], say: Callable[[str], None]) -> dict:
    from app.export import GROUND_VERTICES, file_name

    gf, sdf, usd, geom, vt = _pxr()
    parts = out / "usd"
    parts.mkdir(parents=True, exist_ok=True)
    # the blocks are payloads this stage does not load: each is written, and let go, alone
    stage = usd.Stage.CreateNew(str(out / "grass.usda"), load=usd.Stage.LoadNone)
    geom.SetStageUpAxis(stage, geom.Tokens.y)
    geom.SetStageMetersPerUnit(stage, 1.0)
    world = geom.Xform.Define(stage, "/World")
    stage.SetDefaultPrim(world.GetPrim())
    counts: dict = {"instances": {}, "vertices": {}, "blocks": 0}
    grows = grass_cells(document) if "instances" in what else []
    heights = document.heights()
    spec = document.terrain_spec
    for index, kind in enumerate(document.grass_types):
        if "patch" not in what and "instances" not in what:
            break
        name = file_name(kind.name)
        patch_file = parts / f"patch-{name}.usdc"
        counts["vertices"][kind.name] = _patch(patch_file, kind, gf, sdf, usd, geom, vt)
        holder = geom.Xform.Define(stage, f"/World/{_prim(kind.name)}")
        if "instances" not in what:
            patch = stage.DefinePrim(holder.GetPath().AppendChild("Patch"))
            patch.GetReferences().AddReference(f"./usd/{patch_file.name}")
            continue
        total = 0
        for block in blocks(spec.columns, spec.rows):
            translation, rotation, scale = block_instances(document, grows[index], block, heights)
            if translation.shape[0] == 0:
                continue
            block_file = parts / f"{name}-{block[0]}-{block[1]}.usdc"
            _instancer(block_file, patch_file.name, (translation, rotation, scale), usd, geom, vt)
            prim = stage.DefinePrim(holder.GetPath().AppendChild(f"Cells_{block[0]}_{block[1]}"))
            prim.GetPayloads().AddPayload(f"./usd/{block_file.name}")
            total += translation.shape[0]
            counts["blocks"] += 1
        counts["instances"][kind.name] = total
        say(f"{kind.name}: {total} instances")
    if "terrain" in what:
        step = max(1, math.ceil(max(spec.columns, spec.rows) / (GROUND_VERTICES - 1)))
        m = ground_mesh(document, step)
        layer = usd.Stage.CreateNew(str(parts / "terrain.usdc"))
        geom.SetStageUpAxis(layer, geom.Tokens.y)
        terrain = geom.Mesh.Define(layer, "/Terrain")
        layer.SetDefaultPrim(terrain.GetPrim())
        _mesh(terrain, m, vt)
        st = geom.PrimvarsAPI(terrain).CreatePrimvar(
            "st", sdf.ValueTypeNames.TexCoord2fArray, "vertex"
        )
        st.Set(vt.Vec2fArray.FromNumpy(m["uv"]))  # over maps/ground.png, as in the glTF
        layer.GetRootLayer().Save()
        stage.DefinePrim("/World/Terrain").GetReferences().AddReference("./usd/terrain.usdc")
        counts["ground_vertices"] = int(m["position"].shape[0])
    stage.GetRootLayer().Save()
    return counts


def _prim(name: str) -> str:
    """A prim name from a grass type's name (letters, digits and _; not starting with a
    digit)."""
    safe = "".join(c if c.isalnum() else "_" for c in name)
    return safe if safe[:1].isalpha() else f"Grass_{safe}"


def _mesh(mesh, m: dict, vt) -> None:
    mesh.CreatePointsAttr(vt.Vec3fArray.FromNumpy(m["position"]))
    mesh.CreateNormalsAttr(vt.Vec3fArray.FromNumpy(m["normal"]))
    mesh.SetNormalsInterpolation("vertex")
    triangles = m["indices"].reshape(-1, 3)
    # USD meshes wind counter-clockwise seen from the front, as glTF and Sward do
    mesh.CreateFaceVertexCountsAttr(vt.IntArray.FromNumpy(np.full(len(triangles), 3, np.int32)))
    mesh.CreateFaceVertexIndicesAttr(vt.IntArray.FromNumpy(m["indices"].astype(np.int32)))
    mesh.CreateSubdivisionSchemeAttr("none")
    bounds = np.stack([m["position"].min(axis=0), m["position"].max(axis=0)])
    mesh.CreateExtentAttr(vt.Vec3fArray.FromNumpy(bounds.astype(np.float32)))


def _patch(path: Path, kind, gf, sdf, usd, geom, vt) -> int:
    """The patch as a Mesh at /Patch of its own layer."""
    m = patch_mesh(generate_patch(kind.params))
    stage = usd.Stage.CreateNew(str(path))
    geom.SetStageUpAxis(stage, geom.Tokens.y)
    mesh = geom.Mesh.Define(stage, "/Patch")
    stage.SetDefaultPrim(mesh.GetPrim())
    _mesh(mesh, m, vt)
    mesh.CreateDoubleSidedAttr(True)  # a blade is one strip seen from both sides
    primvars = geom.PrimvarsAPI(mesh)
    color = primvars.CreatePrimvar("displayColor", sdf.ValueTypeNames.Color3fArray, "vertex")
    color.Set(vt.Vec3fArray.FromNumpy(m["color"]))
    st = primvars.CreatePrimvar("st", sdf.ValueTypeNames.TexCoord2fArray, "vertex")
    st.Set(vt.Vec2fArray.FromNumpy(m["uv"]))
    threshold = primvars.CreatePrimvar("threshold", sdf.ValueTypeNames.FloatArray, "vertex")
    threshold.Set(vt.FloatArray.FromNumpy(m["threshold"]))
    for name in ("ctrl1", "ctrl2"):  # the blade's curve from its root, as glTF's _CURVE1/2
        curve = primvars.CreatePrimvar(
            name.replace("ctrl", "curve"), sdf.ValueTypeNames.Vector3fArray, "vertex"
        )
        curve.Set(vt.Vec3fArray.FromNumpy(m[name]))
    stage.GetRootLayer().Save()
    return int(m["position"].shape[0])


def _instancer(path: Path, patch: str, moves: tuple, usd, geom, vt) -> None:
    """One block's PointInstancer at /Instances, its prototype the patch layer; `moves`:
    translations, rotations (x, y, z, w) and scales."""
    translation, rotation, scale = moves
    stage = usd.Stage.CreateNew(str(path))
    geom.SetStageUpAxis(stage, geom.Tokens.y)
    instancer = geom.PointInstancer.Define(stage, "/Instances")
    stage.SetDefaultPrim(instancer.GetPrim())
    prototype = stage.DefinePrim("/Instances/Prototypes/Patch")
    prototype.GetReferences().AddReference(f"./{patch}")
    instancer.CreatePrototypesRel().SetTargets([prototype.GetPath()])
    instancer.CreatePositionsAttr(vt.Vec3fArray.FromNumpy(translation))
    instancer.CreateScalesAttr(vt.Vec3fArray.FromNumpy(scale))
    # GfQuath holds its imaginary part first, as glTF does: (x, y, z, w)
    xyzw = np.ascontiguousarray(rotation, np.float16)
    instancer.CreateOrientationsAttr(vt.QuathArray.FromNumpy(xyzw))
    instancer.CreateProtoIndicesAttr(
        vt.IntArray.FromNumpy(np.zeros(translation.shape[0], np.int32))
    )
    stage.GetRootLayer().Save()
