"""Props (core/props.py): boxes and rocks, each shape in one instanced draw; part of t_m with
the ground. A rock is one mesh for every rock (an icosphere pushed in and out by a smooth
noise, flattened where it sits), turned and stretched per instance."""

from __future__ import annotations

import moderngl
import numpy as np

from core.props import PROP_DTYPE, SHAPES
from render.buffers import upload
from render.shaders import load_program
from render.uniforms import FrameUniforms


def _cube() -> np.ndarray:
    """36 vertices (position, normal, cavity) of a unit cube centred on the origin, faces
    outward."""
    verts = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = np.zeros(3)
            n[axis] = sign
            u, v = np.roll(np.eye(3), 1, axis=0)[axis], np.roll(np.eye(3), 2, axis=0)[axis]
            if sign > 0:  # u × v = n: counter-clockwise seen from outside
                u, v = v, u
            c = n * 0.5
            quad = [c - u / 2 - v / 2, c + u / 2 - v / 2, c + u / 2 + v / 2, c - u / 2 + v / 2]
            for k in (0, 1, 2, 0, 2, 3):
                verts.append(np.concatenate([quad[k], n, [1.0]]))
    return np.array(verts, np.float32)


def _icosphere(subdivisions: int) -> tuple[np.ndarray, np.ndarray]:
    """Unit-sphere vertices and counter-clockwise (seen from outside) triangles."""
    t = (1.0 + 5**0.5) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]  # fmt: skip
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]  # fmt: skip
    verts = [np.array(p, np.float64) / np.linalg.norm(p) for p in v]

    def middle(a: int, b: int, cache: dict[tuple[int, int], int]) -> int:
        key = (min(a, b), max(a, b))
        if key not in cache:
            m = verts[a] + verts[b]
            verts.append(m / np.linalg.norm(m))
            cache[key] = len(verts) - 1
        return cache[key]

    for _ in range(subdivisions):
        cache: dict[tuple[int, int], int] = {}

        faces = [
            tri
            for a, b, c in faces
            for ab, bc, ca in [(middle(a, b, cache), middle(b, c, cache), middle(c, a, cache))]
            for tri in ((a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca))
        ]
    return np.array(verts), np.array(faces)


def _rock(subdivisions: int = 3, seed: int = 4) -> np.ndarray:
    """Vertices (position, normal, cavity) of a rock filling the unit cube centred on the
    origin: a sphere moved in and out by a few random smooth waves, its foot flattened; cavity
    (0 … 1) is how far out a vertex stands, for the shading of hollows."""
    rng = np.random.default_rng(seed)
    p, faces = _icosphere(subdivisions)
    radius = np.ones(len(p))
    for frequency, amplitude in ((1.5, 0.22), (3.0, 0.1), (6.0, 0.04)):
        for _ in range(3):
            axis = rng.normal(size=3)
            axis /= np.linalg.norm(axis)
            radius += amplitude * np.sin(frequency * (p @ axis) * np.pi + rng.uniform(0, 6.3))
    q = p * radius[:, None]
    q[:, 1] = np.maximum(q[:, 1], -0.45 * np.abs(q[:, 1]).max())  # sits on a flat foot
    lo, hi = q.min(axis=0), q.max(axis=0)
    q = (q - (lo + hi) / 2.0) / (hi - lo)  # fills the unit cube
    tri = q[faces]
    face_n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normals = np.zeros_like(q)
    for k in range(3):
        np.add.at(normals, faces[:, k], face_n)
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    cavity = (radius - radius.min()) / max(np.ptp(radius), 1e-9)
    idx = faces.ravel()
    return np.concatenate([q[idx], normals[idx], cavity[idx, None]], axis=1).astype(np.float32)


class _Shape:
    """One mesh and the instances drawn with it."""

    def __init__(self, ctx: moderngl.Context, program: moderngl.Program, mesh: np.ndarray):
        self.ctx = ctx
        self.program = program
        self.vbo = ctx.buffer(mesh.tobytes())
        self.instances: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        self.count = 0

    def set_instances(self, props: np.ndarray) -> None:
        self.count = int(props.size)
        data = props if props.size else np.zeros(1, PROP_DTYPE)
        buf = upload(self.ctx, self.instances, data, grow_only=True)
        if buf is not self.instances or self.vao is None:
            self.instances = buf
            if self.vao is not None:
                self.vao.release()
            self.vao = self.ctx.vertex_array(
                self.program,
                [
                    (self.vbo, "3f 3f 1f", "in_position", "in_normal", "in_cavity"),
                    (self.instances, "3f 3f 3f 4x/i", "in_centre", "in_size", "in_color"),
                ],
            )

    def draw(self, rock: bool) -> None:
        if self.count and self.vao is not None:
            self.program["u_rock"].value = 1.0 if rock else 0.0
            self.vao.render(moderngl.TRIANGLES, instances=self.count)

    def release(self) -> None:
        for obj in (self.vao, self.instances, self.vbo):
            if obj is not None:
                obj.release()


class PropRenderer:
    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = load_program(ctx, "props.glsl")
        self.shapes = {
            "box": _Shape(ctx, self.program, _cube()),
            "rock": _Shape(ctx, self.program, _rock()),
        }
        self.count = 0
        self.boxes = np.zeros(0, PROP_DTYPE)  # what is drawn: centres on the ground as it is

    def set_props(self, props: np.ndarray) -> None:
        if props.dtype != PROP_DTYPE:
            raise TypeError("props must be a PROP_DTYPE array")
        self.count = int(props.size)
        self.boxes = props.copy()
        for index, name in enumerate(SHAPES):
            self.shapes[name].set_instances(props[props["shape"] == index])

    def draw(self, frame: FrameUniforms) -> None:
        if not self.count:
            return
        frame.apply(self.program)
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        for name, shape in self.shapes.items():
            shape.draw(rock=name == "rock")
        self.ctx.disable(moderngl.CULL_FACE)

    def release(self) -> None:
        for shape in self.shapes.values():
            shape.release()
