"""Reading project files in bounded time and memory (issue: files are data): each case is loaded
in a fresh process, which reports its wall time and its peak resident memory; for the valid
project the peak is set against the size of its maps (goal: within ~1.5× of the maps, and every
case within 10 s and 2 GB).

Run: `sward bench --suite files --out results.json` (SWARD_BENCH_MAP=4096 for the largest maps a
project may hold; the default 2048 keeps the run short).
"""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import numpy as np

PROBE = """
import json, sys, time
from core.project_file import ProjectError, load_project
def hwm():  # peak resident memory of this process image, kB (ru_maxrss survives exec)
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1])
base = hwm()
start = time.perf_counter()
try:
    doc = load_project(sys.argv[1])
    outcome, size = "loaded", int(doc.maps.stack.nbytes)
except ProjectError as exc:
    outcome, size = "refused: " + str(exc)[-60:], 0
took = time.perf_counter() - start
peak = hwm()
print(json.dumps({"s": took, "peak_mb": peak / 1024, "base_mb": base / 1024,
                  "outcome": outcome, "maps_mb": size / 2**20}))
"""


def _probe(path: Path) -> dict:
    run = subprocess.run(
        [sys.executable, "-c", PROBE, str(path)], capture_output=True, text=True, timeout=120
    )
    if run.returncode:
        raise RuntimeError(f"loading {path.name} failed: {run.stderr.strip()[-300:]}")
    return json.loads(run.stdout)


def _valid(folder: Path, side: int) -> Path:
    from app.scenes import get_scene
    from core.design_maps import DesignMaps
    from core.project_file import save_project

    doc = get_scene("patch-grid").document()
    maps = DesignMaps(side)
    rng = np.random.default_rng(1)
    maps.stack[0, :, :, 0] = rng.random((side, side), np.float32)  # some entropy to inflate
    doc.maps = maps
    path = folder / f"maps{side}.sward"
    save_project(path, doc)
    return path


def _malformed(folder: Path, valid: Path) -> list[Path]:
    with zipfile.ZipFile(valid) as z:
        text = z.read("project.json")
    huge = io.BytesIO()
    np.lib.format.write_array_header_1_0(
        huge, {"descr": "<f4", "fortran_order": False, "shape": (5, 100000, 100000, 4)}
    )
    inner = io.BytesIO()
    with zipfile.ZipFile(inner, "w") as z:
        z.writestr("stack.npy", huge.getvalue())
    cases = {
        "header_200gb": (text, inner.getvalue()),
        "json_bomb": (b" " * (3 << 30 >> 6), b""),  # 48 MB of spaces, a few KB packed
        "deep_json": (b"[" * 100000 + b"]" * 100000, b""),
    }
    paths = []
    for name, (project, maps) in cases.items():
        path = folder / f"{name}.sward"
        with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as z:
            z.writestr("project.json", project)
            z.writestr("maps.npz", maps)
        paths.append(path)
    return paths


def files() -> list[dict]:
    side = int(os.environ.get("SWARD_BENCH_MAP", "2048"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        valid = _valid(folder, side)
        for path in [valid, *_malformed(folder, valid)]:
            r = _probe(path)
            extra = r["peak_mb"] - r["base_mb"]
            rows.append(
                {
                    "name": path.stem,
                    "seconds": r["s"],
                    "peak_mb": r["peak_mb"],
                    "load_mb": extra,
                    "maps_mb": r["maps_mb"],
                    "peak_over_maps": extra / r["maps_mb"] if r["maps_mb"] else 0.0,
                    "outcome": r["outcome"],
                }
            )
    return rows


BAD_VALUES = ["text", [], {}, None, True, -1, 0, 0.5, 1e308, 10**12, -1e9, [1, 2, 3, 4, 5]]


def corpus() -> dict:
    """Every field of a valid project given every bad value, loaded in one process: how many
    were refused, the slowest case, and the process's peak memory for the whole corpus."""
    import time

    from app.scenes import get_scene
    from core.project_file import ProjectError, load_project, save_project

    def leaves(value, path=()):
        if isinstance(value, dict):
            for k, v in value.items():
                yield from leaves(v, (*path, k))
        elif (
            isinstance(value, list) and value and not all(isinstance(v, int | float) for v in value)
        ):
            for i, v in enumerate(value):
                yield from leaves(v, (*path, i))
        else:
            yield path

    counts = {"refused": 0, "loaded": 0}
    slowest = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        good = Path(tmp) / "good.sward"
        save_project(good, get_scene("meadow").document())
        with zipfile.ZipFile(good) as z:
            data, maps = json.loads(z.read("project.json")), z.read("maps.npz")
        for where in leaves(data):
            for value in BAD_VALUES:
                variant = json.loads(json.dumps(data))
                node = variant
                for key in where[:-1]:
                    node = node[key]
                node[where[-1]] = value
                path = Path(tmp) / "v.sward"
                with zipfile.ZipFile(path, "w") as z:
                    z.writestr("project.json", json.dumps(variant))
                    z.writestr("maps.npz", maps)
                start = time.perf_counter()
                try:
                    load_project(path)
                    counts["loaded"] += 1
                except ProjectError:
                    counts["refused"] += 1
                slowest = max(slowest, time.perf_counter() - start)
    with open("/proc/self/status") as status:
        peak = next(int(line.split()[1]) for line in status if line.startswith("VmHWM:"))
    return {"name": "field_corpus", **counts, "slowest_s": slowest, "process_peak_mb": peak / 1024}


def run() -> list[dict]:
    rows = files()
    rows.append({k: float(v) if isinstance(v, int) else v for k, v in corpus().items()})
    return rows


if __name__ == "__main__":
    for row in run():
        print(row)
