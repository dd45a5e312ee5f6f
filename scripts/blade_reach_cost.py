"""What the wind's blade_reach costs: the meadow's default frame at 950 × 720 (as `sward bench
--suite wind` draws it) in still air and with the wind blowing at each reach, frame by frame in
turn so that the machine's drift falls on all alike; the medians of t_a, t_g, t_v, t_i and the
share each reach adds to still air's t_a.

    .venv/bin/python scripts/blade_reach_cost.py [--reach 1.0 1.1 1.15 1.2 1.25] [--frames 11]

Prints a table and one JSON line. What each reach does to the agreement with all-geometry:
`sward quality --scene meadow --camera default --camera path --wind on --time T --blade-reach R`.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

SIZE = (950, 720)
PARTS = ("t_a_ms", "t_g_ms", "t_v_ms", "t_i_ms")


def main() -> None:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--reach", type=float, nargs="+", default=[1.0, 1.1, 1.15, 1.2, 1.25])
    parser.add_argument("--frames", type=int, default=11)
    args = parser.parse_args()
    document = get_scene("meadow").document()
    camera = document.camera()
    winds = {"still": document.wind.replace(enabled=False)}
    for reach in args.reach:
        winds[f"{reach:g}"] = document.wind.replace(enabled=True, blade_reach=reach)
    times: dict[str, list[tuple[float, ...]]] = {name: [] for name in winds}
    with HeadlessRenderer(document) as renderer:
        renderer.render(camera, SIZE)  # slices converted, buffers made
        for frame in range(args.frames):
            for name, wind in winds.items():
                document.wind = wind
                renderer.pipeline.time = 0.1 * frame
                _, stats = renderer.render(camera, SIZE, measure=True)
                times[name].append(tuple(getattr(stats, part) for part in PARTS))
    medians = {
        name: [statistics.median(row[i] for row in rows) for i in range(len(PARTS))]
        for name, rows in times.items()
    }
    still = medians["still"][0]
    print(f"{'wind':>6} " + " ".join(f"{p[:3]:>7}" for p in PARTS) + "   added")
    result = {}
    for name, values in medians.items():
        added = 100.0 * (values[0] - still) / still
        print(f"{name:>6} " + " ".join(f"{v:7.1f}" for v in values) + f"  {added:+5.1f} %")
        result[name] = {**dict(zip(PARTS, values, strict=True)), "added_t_a_percent": added}
    print(json.dumps(result))


if __name__ == "__main__":
    main()
