"""Buffer uploads and the per-instance vertex layout shared by the renderers."""

from __future__ import annotations

import moderngl
import numpy as np

from core.grid import INSTANCE_DTYPE
from render.shaders import reads

# (attribute, float count) in the order of core.grid.INSTANCE_DTYPE's fields.
INSTANCE_ATTRIBUTES = (
    ("in_origin", 2),
    ("in_cell_density", 1),
    ("in_lod", 2),
    ("in_size", 2),
    ("in_mirror", 2),
    ("in_config", 4),
    ("in_ground", 2),
)
assert sum(n for _, n in INSTANCE_ATTRIBUTES) * 4 == INSTANCE_DTYPE.itemsize


def upload(
    ctx: moderngl.Context, buf: moderngl.Buffer | None, data: np.ndarray, grow_only: bool = False
) -> moderngl.Buffer:
    """Write `data` into `buf` when it fits (exactly, or at least with grow_only), else a new one."""
    raw = np.ascontiguousarray(data).tobytes()
    if buf is not None and (buf.size == len(raw) or (grow_only and buf.size >= len(raw))):
        buf.write(raw)
        return buf
    if buf is not None:
        buf.release()
    return ctx.buffer(raw)


def layout(
    program: moderngl.Program,
    buffer: moderngl.Buffer,
    attributes: tuple[tuple[str, int], ...],
    suffix: str = "",
) -> tuple:
    """A vertex-array entry that skips the attributes the program does not use."""
    parts, names = [], []
    for name, count in attributes:
        if reads(program, name):
            parts.append(f"{count}f")
            names.append(name)
        else:
            parts.append(f"{count * 4}x")
    return (buffer, " ".join(parts) + suffix, *names)


def instance_layout(program: moderngl.Program, buffer: moderngl.Buffer) -> tuple:
    return layout(program, buffer, INSTANCE_ATTRIBUTES, "/i")


class InstancedRenderer:
    """set_instances for every renderer: a grow-only instance buffer, so selecting a new subset
    each frame writes into it without new GL objects; the vertex array is rebuilt only when the
    buffer itself is new. Subclasses give `_make_vao` (None while they cannot draw yet)."""

    ctx: moderngl.Context
    program: moderngl.Program
    instances: moderngl.Buffer | None
    vao: moderngl.VertexArray | None
    instance_count: int
    # a second per-instance buffer of float32 rows some renderers draw with: its layout
    # ("4f 4f/i", attribute names), and its rows where set_instances is given none
    rows_layout: tuple[str, tuple[str, ...]] | None = None
    rows_buffer: moderngl.Buffer | None = None

    def default_rows(self, instances: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def use_program(self, program: moderngl.Program) -> None:
        """Draw with `program` from now on: a variant of the same file (the same inputs), such
        as its still-air one (render/shaders.py wind_defines). The vertex array of the variant
        before is kept for when it comes back (a frame may switch between variants pass by
        pass); one for this variant is made when there is none."""
        if program is self.program:
            return
        spare = self.__dict__.setdefault("_spare_vaos", {})
        if self.vao is not None:
            spare[self.program] = self.vao
        self.program = program
        self.vao = spare.pop(program, None)
        if self.vao is None and self.instances is not None:
            self.vao = self._make_vao()

    def set_instances(self, instances: np.ndarray, rows: np.ndarray | None = None) -> None:
        """The cells to draw: an INSTANCE_DTYPE array; with rows_layout, one row of its second
        buffer per cell (default_rows where None)."""
        if instances.dtype != INSTANCE_DTYPE:
            raise TypeError("instances must be an INSTANCE_DTYPE array")
        self.instance_count = int(instances.size)
        fresh = False
        if self.rows_layout is not None:
            rows = self.default_rows(instances) if rows is None else rows
            if len(rows) != instances.size:
                raise ValueError("one row of the second buffer per instance")
            data = rows if len(rows) else np.zeros((1, rows.shape[1]), np.float32)
            buf = upload(self.ctx, self.rows_buffer, np.asarray(data, np.float32), grow_only=True)
            fresh = buf is not self.rows_buffer
            self.rows_buffer = buf
        data = instances if instances.size else np.zeros(1, INSTANCE_DTYPE)
        buf = upload(self.ctx, self.instances, data, grow_only=True)
        if buf is not self.instances or fresh:
            self.instances = buf
            self._rebuild_vao()

    def _buffers(self, corners: tuple) -> list[tuple]:
        """The vertex array's buffers: the mesh's `corners` entry, the instances and the
        second buffer's attributes that the program reads."""
        out = [corners, instance_layout(self.program, self.instances)]
        if self.rows_layout is not None and self.rows_buffer is not None:
            fmt, names = self.rows_layout
            if all(reads(self.program, name) for name in names):
                out.append((self.rows_buffer, fmt, *names))
        return out

    def _rebuild_vao(self) -> None:
        """A vertex array for new buffers; those of other variants go (they read the old)."""
        self._release_vaos()
        self.vao = self._make_vao()

    def _release_vaos(self) -> None:
        for vao in self.__dict__.pop("_spare_vaos", {}).values():
            vao.release()
        if self.vao is not None:
            self.vao.release()
            self.vao = None

    def _make_vao(self) -> moderngl.VertexArray | None:
        raise NotImplementedError
