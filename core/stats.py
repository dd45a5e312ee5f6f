"""Per-frame statistics (thesis ch. 7): times in ms and instance counts per technique."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field


@dataclass
class FrameStats:
    """t_a whole frame; t_q LOD selection on the CPU (the quadtree traversal, the bare-cell
    filter, core/draw_list.py); t_u the instance uploads of what was selected; t_g / t_v / t_i geometry, volume and image-based grass; t_m the rest of the
    scenery (ground, props); t_s the blades' shadows on the ground (when the light casts them); t_o clearing and resolving the multisampled image. c_* are
    instance counts."""

    t_a_ms: float = 0.0
    t_q_ms: float = 0.0
    t_u_ms: float = 0.0
    t_g_ms: float = 0.0
    t_v_ms: float = 0.0
    t_i_ms: float = 0.0
    t_m_ms: float = 0.0
    t_s_ms: float = 0.0
    t_o_ms: float = 0.0
    c_g: int = 0
    c_v: int = 0
    c_i: int = 0
    blades: int = 0
    triangles: int = 0
    width: int = 0
    height: int = 0
    draft: bool = False  # the quick frame that answers input (the draft process's)
    # time.monotonic() when the state the frame shows was taken (the designer's latency)
    state_time: float = 0.0
    # per grass type and LOD level drawn: (type index, representation, slices, instances)
    levels: list[tuple[int, str, int, int]] = field(default_factory=list)

    def add_instances(self, representation: str, count: int) -> None:
        """`count` more instances drawn as geometry, volume or image-based grass."""
        if representation == "geometry":
            self.c_g += count
        elif representation == "volume":
            self.c_v += count
        else:
            self.c_i += count

    def add_time(self, representation: str, ms: float) -> None:
        """`ms` more spent drawing geometry, volume or image-based grass."""
        if representation == "geometry":
            self.t_g_ms += ms
        elif representation == "volume":
            self.t_v_ms += ms
        else:
            self.t_i_ms += ms

    def level_count(self, grass_type: int, representation: str, slices: int = 0) -> int:
        """Instances the LOD level (representation, slices) of one grass type drew."""
        return sum(
            n
            for i, r, s, n in self.levels
            if (i, r) == (grass_type, representation) and s == slices
        )

    @property
    def fps(self) -> float:
        return 1000.0 / self.t_a_ms if self.t_a_ms > 0 else 0.0

    @property
    def parts_ms(self) -> float:
        """The measured parts; with measured frames they add up to nearly t_a (the rest is
        Python between the passes)."""
        return (
            self.t_q_ms
            + self.t_u_ms
            + self.t_g_ms
            + self.t_v_ms
            + self.t_i_ms
            + self.t_m_ms
            + self.t_s_ms
            + self.t_o_ms
        )

    def to_dict(self) -> dict:
        d = asdict(self)
        d["fps"] = round(self.fps, 2)
        return d
