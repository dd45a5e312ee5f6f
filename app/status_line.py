"""The designer's status line: what the last frame drew and what it cost, or the Quality view's
figures (plain text, no Qt: app/designer.py sets it)."""

from __future__ import annotations

from core.stats import FrameStats


def status_text(
    stats: FrameStats, busy: str = "", fly_speed: float | None = None, wind_on_drafts: bool = False
) -> str:
    """Blades, triangles, the cells of each representation and the frame's time and its parts
    (a draft's as a whole); `busy`: what a render process says it is doing; `fly_speed`: in fly
    mode, its speed; `wind_on_drafts`: the wind moves on with drafts, no full frame follows."""
    if stats.draft:  # a draft is timed as a whole only
        follows = (
            "the wind moves on with drafts (View → Sharp wind frames: full ones)"
            if wind_on_drafts
            else "full quality follows"
        )
        timing = f"draft {stats.t_a_ms:.0f} ms, {follows}"
    else:
        # the ground and props, and the blades' shadows where drawn: with shadows on they can
        # cost more than the three representations together
        shadows = f" · shadows {stats.t_s_ms:.0f}" if stats.t_s_ms > 0 else ""
        timing = (
            f"frame {stats.t_a_ms:.0f} ms (g {stats.t_g_ms:.0f} · v {stats.t_v_ms:.0f} · "
            f"i {stats.t_i_ms:.0f} · ground {stats.t_m_ms:.0f}{shadows} ms)"
        )
    return (
        (f"{busy} · " if busy else "")
        + f"{stats.blades:,} blades · {stats.triangles:,} triangles · "
        f"cells g/v/i {stats.c_g}/{stats.c_v}/{stats.c_i} · {timing}"
        + (
            f"  ·  fly mode, {fly_speed:.3g} units/s (WASD, Q/E; wheel: speed; F to leave)"
            if fly_speed is not None
            else ""
        )
    )


def quality_text(figures: dict) -> str:
    """One status line of the Quality view's figures."""
    lod = figures["lod"]
    parts = [
        f"{name} {t['flip_quarter']:.3f}"
        for name, t in figures["techniques"].items()
        if t["flip_quarter"] is not None
    ]
    return (
        f"quality against all-geometry: FLIP {lod['flip_quarter']:.3f} (quarter resolution; "
        f"{', '.join(parts) or 'no grass'}) · block colour {lod['block_color']:.3f} · "
        f"LOD {figures['lod_ms']:.0f} ms, all-geometry {figures['geometry_ms']:.0f} ms "
        f"({figures['speedup']:.1f}x faster)"
        + (" · all-geometry frame kept from before" if figures.get("reference_kept") else "")
    )
