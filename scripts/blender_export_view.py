"""Renders a `sward export` (glTF) in Blender, instances included, to a PNG: what the export
looks like in a 3D tool. Blender's glTF importer reads EXT_mesh_gpu_instancing only from
Blender 3.6 on; this script places each block's instances itself (geometry nodes: the patch on
every point with its rotation and scale), so it works with older ones too.

    blender -b --python scripts/blender_export_view.py -- EXPORT_DIR OUT.png EYE TARGET

EYE and TARGET are x,y,z in Sward's world (y up), e.g. the meadow's default camera
7,4.5,27 0,1.5,10. Without a display, run it under `xvfb-run -a` (EEVEE needs OpenGL). Blender
draws what the file holds: every blade of every instance, with no thinning by the density map
(an engine does that with _THRESHOLD, docs/export.md)."""

import json
import math
import sys

import bpy
import numpy

numpy.bool = bool  # Debian's Blender 3.4 glTF importer still names numpy.bool (gone in 1.24)
import numpy as np  # noqa: E402
from mathutils import Quaternion, Vector  # noqa: E402


def main(folder: str, out: str, eye: str, target: str) -> None:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=f"{folder}/grass.gltf")
    with open(f"{folder}/grass.gltf") as f:
        doc = json.load(f)
    with open(f"{folder}/grass.bin", "rb") as f:
        data = f.read()

    def read(index: int, width: int) -> np.ndarray:
        a = doc["accessors"][index]
        view = doc["bufferViews"][a["bufferView"]]
        start = view["byteOffset"] + a.get("byteOffset", 0)
        return np.frombuffer(data, np.float32, a["count"] * width, start).reshape(-1, width)

    for node in doc["nodes"]:
        moves = node.get("extensions", {}).get("EXT_mesh_gpu_instancing", {}).get("attributes")
        if moves:
            _instance(node["name"], read(moves["TRANSLATION"], 3), read(moves["ROTATION"], 4),
                      read(moves["SCALE"], 3))  # fmt: skip
    scene = bpy.context.scene
    _camera(scene, [float(v) for v in eye.split(",")], [float(v) for v in target.split(",")])
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    scene.collection.objects.link(sun)
    sun.rotation_euler = (math.radians(40), 0, math.radians(30))
    sun.data.energy = 3.0
    world = bpy.data.worlds.new("sky")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs[0].default_value = (0.55, 0.7, 0.9, 1)
    world.node_tree.nodes["Background"].inputs[1].default_value = 0.8
    scene.render.engine = "BLENDER_EEVEE"
    scene.eevee.taa_render_samples = 4
    scene.render.resolution_x, scene.render.resolution_y = 960, 540
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)


def _blender(v: np.ndarray) -> np.ndarray:
    """glTF's y-up axes as Blender's z-up ones, as its glTF importer turns them."""
    return np.stack([v[:, 0], -v[:, 2], v[:, 1]], axis=1)


def _instance(name: str, translation, rotation, scale) -> None:
    """The block's patch (imported once at the origin) on a point per instance."""
    patch = bpy.data.objects[name]
    patch.hide_render = True
    mesh = bpy.data.meshes.new(f"{name} points")
    mesh.vertices.add(len(translation))
    mesh.vertices.foreach_set("co", _blender(translation).ravel())
    turn = [list(Quaternion((w, x, -z, y)).to_euler("XYZ")) for x, y, z, w in rotation]
    for attribute, values in (("turn", np.array(turn)), ("scale", scale[:, [0, 2, 1]])):
        mesh.attributes.new(attribute, "FLOAT_VECTOR", "POINT").data.foreach_set(
            "vector", np.asarray(values, np.float32).ravel()
        )
    holder = bpy.data.objects.new(f"{name} points", mesh)
    bpy.context.scene.collection.objects.link(holder)
    tree = bpy.data.node_groups.new(name, "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    given, result = tree.nodes.new("NodeGroupInput"), tree.nodes.new("NodeGroupOutput")
    info = tree.nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = patch
    place = tree.nodes.new("GeometryNodeInstanceOnPoints")
    tree.links.new(given.outputs[0], place.inputs["Points"])
    tree.links.new(info.outputs["Geometry"], place.inputs["Instance"])
    for attribute, socket in (("turn", "Rotation"), ("scale", "Scale")):
        named = tree.nodes.new("GeometryNodeInputNamedAttribute")
        named.data_type = "FLOAT_VECTOR"
        named.inputs["Name"].default_value = attribute
        tree.links.new(named.outputs["Attribute"], place.inputs[socket])
    tree.links.new(place.outputs["Instances"], result.inputs[0])
    holder.modifiers.new("instances", "NODES").node_group = tree


def _camera(scene, eye: list[float], target: list[float]) -> None:
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam)
    scene.camera = cam
    cam.location = Vector((eye[0], -eye[2], eye[1]))
    look = Vector((target[0], -target[2], target[1])) - cam.location
    cam.rotation_euler = look.to_track_quat("-Z", "Y").to_euler()
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = math.radians(50.0)  # Sward's cameras' field of view


if __name__ == "__main__":
    main(*sys.argv[sys.argv.index("--") + 1 :][:4])
