"""Buffer uploads shared by the renderers."""

from __future__ import annotations

import moderngl
import numpy as np

from core.grid import INSTANCE_DTYPE

SIZED_INSTANCE_DTYPE = np.dtype([("i", INSTANCE_DTYPE), ("size", np.float32)])
# vertex-array format of SIZED_INSTANCE_DTYPE and the attribute names it feeds
SIZED_INSTANCE_FORMAT = ("2f 1f 2f 1f/i", "in_origin", "in_cell_density", "in_lod", "in_size")


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


def sized_instances(instances: np.ndarray, sizes: np.ndarray | None = None) -> np.ndarray:
    """Instances with their (macro-)cell edge length, for the carrier-based renderers."""
    if instances.dtype != INSTANCE_DTYPE:
        raise TypeError("instances must be an INSTANCE_DTYPE array")
    data = np.zeros(max(instances.size, 1), dtype=SIZED_INSTANCE_DTYPE)
    if instances.size:
        data["i"] = instances
        data["size"] = 1.0 if sizes is None else sizes
    return data


class SizedInstances:
    """set_instances for the carrier renderers (volume, image): a grow-only instance buffer and a
    vertex array rebuilt only when the buffer itself is new. Subclasses give `_make_vao`."""

    ctx: moderngl.Context
    instances: moderngl.Buffer | None
    vao: moderngl.VertexArray | None
    instance_count: int

    def set_instances(self, instances: np.ndarray, sizes: np.ndarray | None = None) -> None:
        """Cells to draw, each with its macro-cell edge in cells."""
        self.instance_count = int(instances.size)
        buf = upload(self.ctx, self.instances, sized_instances(instances, sizes), grow_only=True)
        if buf is self.instances:
            return
        self.instances = buf
        if self.vao is not None:
            self.vao.release()
        self.vao = self._make_vao()

    def _make_vao(self) -> moderngl.VertexArray:
        raise NotImplementedError
