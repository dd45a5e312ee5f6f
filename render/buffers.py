"""Buffer uploads and the per-instance vertex layout shared by the renderers."""

from __future__ import annotations

import moderngl
import numpy as np

from core.grid import INSTANCE_DTYPE

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
        if name in program:
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

    def set_instances(self, instances: np.ndarray) -> None:
        """The cells to draw: an INSTANCE_DTYPE array."""
        if instances.dtype != INSTANCE_DTYPE:
            raise TypeError("instances must be an INSTANCE_DTYPE array")
        self.instance_count = int(instances.size)
        data = instances if instances.size else np.zeros(1, INSTANCE_DTYPE)
        buf = upload(self.ctx, self.instances, data, grow_only=True)
        if buf is self.instances:
            return
        self.instances = buf
        self._rebuild_vao()

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
