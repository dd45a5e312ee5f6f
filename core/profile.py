"""Profiling tables after the thesis's chapter 7: per viewpoint the median, min and max of the
frame statistics over several frames, and the check that the parts add up to the whole."""

from __future__ import annotations

import csv
import io
import json

import numpy as np

from core.stats import FrameStats

COLUMNS = ("fps", "t_a", "t_q", "t_g", "t_v", "t_i", "t_m", "t_s", "c_g", "c_v", "c_i")
# what each column of the overlay means, beside its figures (the thesis's names are short)
MEANING = {
    "fps": "frames a second",
    "t_a": "ms, whole frame",
    "t_q": "ms, LOD selection",
    "t_g": "ms, geometry",
    "t_v": "ms, volume",
    "t_i": "ms, image-based",
    "t_m": "ms, ground and props",
    "t_s": "ms, blade shadows",
    "c_g": "geometry instances",
    "c_v": "volume instances",
    "c_i": "image-based instances",
}
# The parts (t_q + t_u + t_g + t_v + t_i + t_m + t_s + t_o) must lie within this fraction of t_a, plus a
# small fixed allowance for the Python between the measured passes.
SUM_TOLERANCE = 0.10
SUM_ALLOWANCE_MS = 3.0


def _value(stats: FrameStats, column: str) -> float:
    if column == "fps":
        return stats.fps
    if column.startswith("t_"):
        return getattr(stats, f"{column}_ms")
    return float(getattr(stats, column))


def summarize(frames: list[FrameStats]) -> dict[str, dict[str, float]]:
    """{column: {median, min, max}} over the frames, plus the parts' sum as a share of t_a."""
    if not frames:
        raise ValueError("no frames to summarize")
    out = {}
    for column in (*COLUMNS, "t_u", "t_o"):
        values = np.array([_value(f, column) for f in frames])
        out[column] = {
            "median": float(np.median(values)),
            "min": float(values.min()),
            "max": float(values.max()),
        }
    shares = np.array([f.parts_ms / f.t_a_ms for f in frames if f.t_a_ms > 0])
    out["parts_over_t_a"] = {
        "median": float(np.median(shares)),
        "min": float(shares.min()),
        "max": float(shares.max()),
    }
    return out


def parts_add_up(stats: FrameStats) -> bool:
    """t_q + t_u + t_g + t_v + t_i + t_m + t_o lies within the tolerance of t_a (and not above it)."""
    gap = stats.t_a_ms - stats.parts_ms
    return -0.5 <= gap <= SUM_TOLERANCE * stats.t_a_ms + SUM_ALLOWANCE_MS


def table(rows: list[tuple[str, dict[str, dict[str, float]]]]) -> str:
    """The thesis-style table: a block per viewpoint, lines median / min / max."""
    head = f"{'viewpoint':16s}{'':7s}" + "".join(f"{c:>10s}" for c in COLUMNS)
    lines = [head, "-" * len(head)]
    for name, summary in rows:
        for i, stat in enumerate(("median", "min", "max")):
            cells = []
            for column in COLUMNS:
                v = summary[column][stat]
                cells.append(f"{v:10.0f}" if column.startswith("c_") else f"{v:10.2f}")
            label = name if i == 0 else ""
            lines.append(f"{label:16s}{stat:7s}" + "".join(cells))
    return "\n".join(lines)


WINDOW = 60  # frames the live overlay averages over
RECORD_COLUMNS = (
    "t_a_ms",
    "t_q_ms",
    "t_u_ms",
    "t_g_ms",
    "t_v_ms",
    "t_i_ms",
    "t_m_ms",
    "t_s_ms",
    "t_o_ms",
    "c_g",
    "c_v",
    "c_i",
    "fps",
    "blades",
    "triangles",
    "width",
    "height",
)


def rolling(frames: list[FrameStats]) -> dict[str, tuple[float, float, float]]:
    """{column: (average, min, max)} over the given frames (the live timing overlay)."""
    out = {}
    for column in COLUMNS:
        values = np.array([_value(f, column) for f in frames]) if frames else np.zeros(1)
        out[column] = (float(values.mean()), float(values.min()), float(values.max()))
    return out


def overlay_text(frames: list[FrameStats]) -> str:
    """The thesis's table as a small block: a row per column, average / min / max."""
    stats = rolling(frames)
    lines = [f"{'':4s}{'avg':>8s}{'min':>8s}{'max':>8s}   last {len(frames)} frames"]
    for column in COLUMNS:
        avg, lo, hi = stats[column]
        fmt = "{:8.0f}" if column.startswith("c_") else "{:8.1f}"
        figures = "".join(fmt.format(v) for v in (avg, lo, hi))
        lines.append(f"{column:4s}{figures}   {MEANING[column]}")
    return "\n".join(lines)


def frames_csv(frames: list[FrameStats]) -> str:
    """One row per frame, the columns of RECORD_COLUMNS (spreadsheet-friendly)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["frame", *RECORD_COLUMNS])
    for i, f in enumerate(frames):
        d = f.to_dict()
        writer.writerow(
            [i, *(round(d[c], 4) if isinstance(d[c], float) else d[c] for c in RECORD_COLUMNS)]
        )
    return buffer.getvalue()


def frames_json(frames: list[FrameStats], **about) -> str:
    """{about…, "frames": [one stats object per frame]} (the stats JSON of DESIGN.md)."""
    return json.dumps({**about, "frames": [f.to_dict() for f in frames]}, indent=1) + "\n"
