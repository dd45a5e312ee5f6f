"""What the `sward` command line takes in: its parser (the contract in DESIGN.md), the types
of its values, and the document a command works on. Bad input raises CliError: one line."""

from __future__ import annotations

import argparse
import math
import os
from pathlib import Path


class CliError(Exception):
    """Bad input from the command line: printed as one line, exit status 2."""


def _wxh(text: str, what: str, example: str) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"malformed {what} {text!r}; expected WxH, e.g. {example}"
        ) from None
    return w, h


def _size(text: str) -> tuple[int, int]:
    w, h = _wxh(text, "size", "1024x768")
    if not (1 <= w <= 8192 and 1 <= h <= 8192):
        raise argparse.ArgumentTypeError(f"size {text!r} out of range; each side 1 … 8192")
    return w, h


def _cells(text: str) -> tuple[int, int]:
    return _wxh(text, "terrain size", "4096x4096 (cells)")


def _vec3(text: str) -> tuple[float, float, float]:
    try:
        x, y, z = (float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"malformed point {text!r}; expected X,Y,Z") from None
    return x, y, z


def _view_height(text: str) -> float | str:
    if text.lower() in ("none", "off"):
        return "none"
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"malformed view height {text!r}; expected pixels (16 … 16384) or none"
        ) from None
    if not 16 <= value <= 16384:
        raise argparse.ArgumentTypeError(f"view height {text!r} out of range; 16 … 16384 pixels")
    return value


def _times(text: str) -> list[float]:
    """SECONDS, or FROM:TO:STEP (both ends included) for a frame sequence."""
    parts = text.split(":")
    try:
        values = [float(v) for v in parts]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"malformed time {text!r}; expected SECONDS or FROM:TO:STEP, e.g. 0:2:0.04"
        ) from None
    if len(values) not in (1, 3) or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(
            f"malformed time {text!r}; expected SECONDS or FROM:TO:STEP, e.g. 0:2:0.04"
        )
    if len(values) == 1:
        start, stop, step = values[0], values[0], 1.0
    else:
        start, stop, step = values
    if not (0.0 <= start <= 1e6 and 0.0 <= stop <= 1e6):
        raise argparse.ArgumentTypeError(f"time {text!r} out of range; 0 … 1000000 seconds")
    if step <= 0.0 or stop < start:
        raise argparse.ArgumentTypeError(f"time {text!r}: STEP must be > 0 and TO ≥ FROM")
    count = math.floor((stop - start) / step + 1e-9) + 1
    if count > 10_000:
        raise argparse.ArgumentTypeError(f"time {text!r} makes {count} frames; at most 10000")
    return [start + i * step for i in range(count)]


def _time_option(p: argparse.ArgumentParser, metavar: str, more: str) -> None:
    p.add_argument(
        "--time",
        type=_times,
        default=[0.0],
        metavar=metavar,
        help=f"the moment of the wind to draw in seconds (default 0); {more}",
    )


def _wind_option(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--wind",
        type=_wind,
        metavar="on|off|PRESET",
        help="switch the project's wind on or off, or on with a preset's gusts and turbulence "
        "(light-breeze, gusty, storm; the direction kept); default: as the project has it",
    )
    p.add_argument(
        "--blade-reach",
        type=_blade_reach,
        metavar="R",
        help="while the wind blows, the representation after the blades begins R times as far "
        "out as the LOD levels say, the blades run on past it (1 … 2; default: as the project "
        "has it, 1.4 unless set)",
    )


def _wind(text: str) -> str:
    """on, off, or a wind preset's name (core/wind.py PRESETS; '-' for its spaces)."""
    from core.wind import PRESETS

    name = text.replace("-", " ")
    if text in ("on", "off") or name in PRESETS:
        return text if text in ("on", "off") else name
    names = ", ".join(n.replace(" ", "-") for n in PRESETS)
    raise argparse.ArgumentTypeError(f"must be on, off or a preset ({names}), not {text!r}")


def _blade_reach(text: str) -> float:
    from core.wind import RANGES

    low, high = RANGES["blade_reach"]
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not low <= value <= high:
        raise argparse.ArgumentTypeError(f"must be a number from {low:g} to {high:g}, not {text!r}")
    return value


def _lod_view_option(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--lod-view-height",
        type=_view_height,
        metavar="PIXELS",
        help="LOD distances of every grass type hold for a view this tall (50° field of view) "
        "and scale with the view's pixels per radian; none: world units",
    )


def writable(path: Path) -> Path:
    parent = path.resolve().parent
    if not parent.is_dir():
        raise CliError(f"cannot write {path}: folder {parent} does not exist")
    if not os.access(parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise CliError(f"cannot write {path}: permission denied")
    return path


def _document_options(with_project: bool = True) -> argparse.ArgumentParser:
    """The options that choose and adjust the document a command works on."""
    from app.scenes import DEFAULT_SCENE

    p = argparse.ArgumentParser(add_help=False)
    p.add_argument(
        "--scene", default=DEFAULT_SCENE, help=f"built-in scene (default {DEFAULT_SCENE})"
    )
    if with_project:
        p.add_argument("--project", type=Path, help="project file (instead of --scene)")
    _lod_view_option(p)
    _wind_option(p)
    return p


def _only_option(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--only",
        choices=("geometry", "volume", "image"),
        help="draw every cell with one representation",
    )


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="sward", description="Design real-time grass.")
    sub = p.add_subparsers(dest="command")
    document = _document_options()

    r = sub.add_parser("render", parents=[document], help="render one frame headless to a PNG")
    r.add_argument("--camera", help="named camera of the scene")
    r.add_argument("--eye", type=_vec3, help="camera position X,Y,Z (with --target)")
    r.add_argument("--target", type=_vec3, help="point the camera looks at X,Y,Z")
    r.add_argument("--size", type=_size, default=(1024, 768), help="image size WxH")
    _only_option(r)
    r.add_argument(
        "--view",
        choices=("shaded", "techniques", "wind"),
        default="shaded",
        help="techniques: geometry red, volume yellow, image blue; "
        "wind: the grass coloured by its lean (red x, green z)",
    )
    r.add_argument("--preset", help="blade preset instead of the scene's patch")
    r.add_argument("--density", type=float, help="global density 0 … 1")
    r.add_argument("--seed", type=int, help="random seed of the patch")
    r.add_argument(
        "--out",
        type=Path,
        help="PNG file to write; with a time sequence one animated PNG, a PNG a frame "
        "with a pattern such as frames/f%%04d.png, or an MP4 video (name ending .mp4)",
    )
    r.add_argument("--stats", type=Path, help="JSON file for the frame statistics")
    _time_option(r, "SECONDS|FROM:TO:STEP", "or a sequence of frames")

    pr = sub.add_parser(
        "profile", parents=[document], help="frame statistics per viewpoint or along a path"
    )
    pr.add_argument("--path", help="camera path of the scene (default: every named camera)")
    pr.add_argument("--frames", type=int, default=None, help="frames per viewpoint or path")
    pr.add_argument("--size", type=_size, default=(1024, 768), help="image size WxH")
    _only_option(pr)
    pr.add_argument(
        "--out",
        type=Path,
        help="JSON file for every frame and the summaries, or .csv: a row per frame",
    )
    pr.add_argument(
        "--hold-ms",
        type=float,
        metavar="T",
        help="adaptive LOD along --path: one factor on every zone's distances holds the frame "
        "time at T ms; reports how well it held and popping",
    )

    n = sub.add_parser(
        "new",
        parents=[_document_options(with_project=False)],
        help="write a project file started from a built-in scene",
    )
    n.add_argument("file", type=Path, help="project file to write (.sward)")
    n.add_argument(
        "--cells",
        type=_cells,
        help="terrain size WxH in cells (default: the scene's); the maps are resampled",
    )
    n.add_argument(
        "--height-map",
        type=Path,
        help="a height map to import (8- or 16-bit greyscale PNG, e.g. a DEM), resampled to "
        "the project's maps",
    )
    n.add_argument(
        "--species-map",
        type=Path,
        help="a terrain colour image: each grass type grows where it is nearest its blades' "
        "colour, none where the soil's is nearest (its density maps are written)",
    )
    n.add_argument(
        "--height-scale",
        type=float,
        help="world units of the height map's white (default: the scene's, or 10)",
    )

    q = sub.add_parser(
        "quality", parents=[document], help="LOD frame against all-geometry: FLIP, floor, popping"
    )
    _quality_options(q)

    t = sub.add_parser(
        "tune", parents=[document], help="search LOD settings for a frame budget or a quality"
    )
    from app.cli_tune import tune_options  # it imports this module

    tune_options(t)

    e = sub.add_parser(
        "export", parents=[document], help="write the design for engines and 3D tools"
    )
    from app.cli_export import export_options

    export_options(e)

    sub.add_parser("scenes", help="list built-in scenes and their cameras")
    sub.add_parser("info", help="print the OpenGL renderer Sward runs on")
    b = sub.add_parser("bench", help="run the benchmarks and write JSON")
    b.add_argument("--suite", action="append", help="benchmark suite (default: all)")
    b.add_argument("--out", type=Path, help="JSON file for the results")
    return p


def _quality_options(q: argparse.ArgumentParser) -> None:
    _time_option(q, "SECONDS", "both frames of each comparison")
    q.add_argument(
        "--time-step",
        type=float,
        default=0.0,
        metavar="S",
        help="along --path, each frame this many seconds of wind after the one before",
    )
    q.add_argument(
        "--camera",
        action="append",
        help="named camera (repeat for several; default: the "
        "scene's default camera unless --path is given)",
    )
    q.add_argument("--path", help="camera path: popping and agreement along it")
    q.add_argument("--frames", type=int, default=8, help="frames along --path (default 8)")
    q.add_argument("--size", type=_size, default=(480, 270), help="image size WxH")
    q.add_argument(
        "--budget",
        type=float,
        default=120.0,
        help="seconds an all-geometry reference may be expected to take; beyond, it is "
        "estimated instead of drawn (default 120)",
    )
    q.add_argument("--out", type=Path, help="folder for quality.json and the heat maps")
    q.add_argument(
        "--sweep",
        action="store_true",
        help="every built-in scene at every camera and the meadow with each preset and patch "
        "extreme: bare blocks, hand-over steps, region colours, the wind far away, each "
        "against its limit; exit status 1 when one is over (--out: sweep.json and a "
        "contact sheet)",
    )
    q.add_argument(
        "--case",
        action="append",
        metavar="PREFIX",
        help="with --sweep, only the cases whose name starts so (e.g. football, meadow/path)",
    )


def document_of(args: argparse.Namespace):
    """The project of --project, or else a new one from the built-in --scene; with
    --lod-view-height, every grass type's LOD distances set to hold for that view."""
    if getattr(args, "project", None) is not None:
        from core.project_file import ProjectError, load_project

        try:
            document = load_project(args.project)
        except ProjectError as exc:
            raise CliError(str(exc)) from None
    else:
        from app.scenes import get_scene

        try:
            document = get_scene(args.scene).document()
        except KeyError as exc:
            raise CliError(exc.args[0]) from None
    overrides(document, args)
    return document


def overrides(document, args: argparse.Namespace) -> None:
    """--lod-view-height, --wind and --blade-reach, where the command has them."""
    _set_view_height(document, getattr(args, "lod_view_height", None))
    wind = getattr(args, "wind", None)
    if wind is not None:
        from core.wind import PRESETS

        document.wind = document.wind.replace(enabled=wind != "off", **PRESETS.get(wind, {}))
    reach = getattr(args, "blade_reach", None)
    if reach is not None:
        document.wind = document.wind.replace(blade_reach=reach)


def _set_view_height(document, value: float | str | None) -> None:
    if value is not None:
        from core.lod_edit import set_view_heights

        document.set_lods(set_view_heights(document.lods, 0.0 if value == "none" else value))


def known_camera(document, name: str) -> None:
    if name not in document.cameras:
        raise CliError(
            f"unknown camera {name!r} for scene {document.name}; "
            f"cameras: {', '.join(document.cameras)}"
        )


def known_path(document, name: str | None) -> None:
    if name is not None and name not in document.paths:
        known = ", ".join(document.paths) or "none"
        raise CliError(f"unknown camera path {name!r} for scene {document.name}; paths: {known}")


def out_folder(out: Path | None, first: str) -> None:
    """Make the --out folder of a command that writes several files (none: nothing), and check
    that its `first` file can be written there."""
    if out is None:
        return
    if out.exists() and not out.is_dir():
        raise CliError(f"--out {out}: not a folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CliError(f"cannot make {out}: {exc.strerror or exc}") from None
    writable(out / first)
