"""`sward bench`: run benchmark suites from benchmarks/, print a table, write JSON."""

from __future__ import annotations

import json
import sys
from pathlib import Path

# "techniques" is the thesis's Table 7.1 (benchmarks/representations.py)
SUITES = (
    "foundation",
    "conversion",
    "representations",
    "techniques",
    "macrocells",
    "traversal",
    "lod_speedup",
    "brush",
    "preview",
    "edits",
    "latency",
    "files",
    "large_terrain",
    "volume_cost",
    "wind",
    "segments",
    "shadows",
    "cover",
    "heights",
)
MODULES = {"techniques": "representations"}


def _figure(value: float) -> str:
    """Milliseconds and ratios to a tenth; small figures (FLIP, shares) to three digits."""
    return f"{value:,.1f}" if abs(value) >= 10 else f"{value:.3g}"


def run(suites: list[str] | None, out: Path | None) -> int:
    import importlib

    # the latency suite drives a real window for a minute or more: asked for by name only
    chosen = suites or [s for s in SUITES if s not in ("techniques", "latency")]
    unknown = [s for s in chosen if s not in SUITES]
    if unknown:
        print(
            f"sward bench: error: unknown suite {unknown[0]!r}; suites: {', '.join(SUITES)}",
            file=sys.stderr,
        )
        return 2
    results = {}
    for name in chosen:
        module = importlib.import_module(f"benchmarks.{MODULES.get(name, name)}")
        results[name] = module.run()
        for row in results[name]:
            numbers = {k: v for k, v in row.items() if isinstance(v, float)}
            cells = "  ".join(f"{k}={_figure(v)}" for k, v in numbers.items())
            print(f"{name:12s} {row['name']:32s} {cells}")
    if out is not None:
        out.write_text(json.dumps(results, indent=2) + "\n")
        print(f"wrote {out}")
    return 0
