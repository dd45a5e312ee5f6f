"""The `sward` command line (the contract in DESIGN.md)."""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
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


def _writable(path: Path) -> Path:
    parent = path.resolve().parent
    if not parent.is_dir():
        raise CliError(f"cannot write {path}: folder {parent} does not exist")
    if not os.access(parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise CliError(f"cannot write {path}: permission denied")
    return path


def parser() -> argparse.ArgumentParser:
    from app.scenes import DEFAULT_SCENE

    p = argparse.ArgumentParser(prog="sward", description="Design real-time grass.")
    sub = p.add_subparsers(dest="command")

    r = sub.add_parser("render", help="render one frame headless to a PNG")
    r.add_argument(
        "--scene", default=DEFAULT_SCENE, help=f"built-in scene (default {DEFAULT_SCENE})"
    )
    r.add_argument("--project", type=Path, help="project file (instead of --scene)")
    _lod_view_option(r)
    r.add_argument("--camera", help="named camera of the scene")
    r.add_argument("--eye", type=_vec3, help="camera position X,Y,Z (with --target)")
    r.add_argument("--target", type=_vec3, help="point the camera looks at X,Y,Z")
    r.add_argument("--size", type=_size, default=(1024, 768), help="image size WxH")
    r.add_argument(
        "--only",
        choices=("geometry", "volume", "image"),
        help="draw every cell with one representation",
    )
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
    _wind_option(r)

    pr = sub.add_parser("profile", help="frame statistics per viewpoint or along a path")
    pr.add_argument("--scene", default=DEFAULT_SCENE, help="built-in scene")
    pr.add_argument("--project", type=Path, help="project file (instead of --scene)")
    _lod_view_option(pr)
    _wind_option(pr)
    pr.add_argument("--path", help="camera path of the scene (default: every named camera)")
    pr.add_argument("--frames", type=int, default=None, help="frames per viewpoint or path")
    pr.add_argument("--size", type=_size, default=(1024, 768), help="image size WxH")
    pr.add_argument(
        "--only", choices=("geometry", "volume", "image"), help="one representation for all"
    )
    pr.add_argument(
        "--out",
        type=Path,
        help="JSON file for every frame and the summaries, or .csv: a row per frame",
    )

    n = sub.add_parser("new", help="write a project file started from a built-in scene")
    n.add_argument("file", type=Path, help="project file to write (.sward)")
    n.add_argument(
        "--scene", default=DEFAULT_SCENE, help=f"built-in scene (default {DEFAULT_SCENE})"
    )
    _lod_view_option(n)
    _wind_option(n)
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
        "--height-scale",
        type=float,
        help="world units of the height map's white (default: the scene's, or 10)",
    )

    q = sub.add_parser("quality", help="LOD frame against all-geometry: FLIP, floor, popping")
    q.add_argument("--scene", default=DEFAULT_SCENE, help="built-in scene")
    q.add_argument("--project", type=Path, help="project file (instead of --scene)")
    _lod_view_option(q)
    _wind_option(q)
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

    sub.add_parser("scenes", help="list built-in scenes and their cameras")
    sub.add_parser("info", help="print the OpenGL renderer Sward runs on")
    b = sub.add_parser("bench", help="run the benchmarks and write JSON")
    b.add_argument("--suite", action="append", help="benchmark suite (default: all)")
    b.add_argument("--out", type=Path, help="JSON file for the results")
    return p


def _document(args: argparse.Namespace):
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
    _overrides(document, args)
    return document


def _overrides(document, args: argparse.Namespace) -> None:
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


def _known_camera(document, name: str) -> None:
    if name not in document.cameras:
        raise CliError(
            f"unknown camera {name!r} for scene {document.name}; "
            f"cameras: {', '.join(document.cameras)}"
        )


def _known_path(document, name: str | None) -> None:
    if name is not None and name not in document.paths:
        known = ", ".join(document.paths) or "none"
        raise CliError(f"unknown camera path {name!r} for scene {document.name}; paths: {known}")


def cmd_new(args: argparse.Namespace) -> int:
    from core.project_file import ProjectError, save_project

    if args.cells is None:
        document = _document(args)
    else:
        from app.scenes import get_scene

        try:
            document = get_scene(args.scene).resized(*args.cells).document()
        except KeyError as exc:
            raise CliError(exc.args[0]) from None
        except ValueError as exc:
            raise CliError(f"--cells: {exc}") from None
        _overrides(document, args)
    if args.height_map is not None or args.height_scale is not None:
        _import_heights(document, args.height_map, args.height_scale)
    _writable(args.file)
    try:
        save_project(args.file, document)
    except ProjectError as exc:
        raise CliError(str(exc)) from None
    t = document.terrain_spec
    print(f"wrote {args.file} (scene {document.name}, {t.columns} × {t.rows} cells)")
    return 0


def _import_heights(document, path: Path | None, scale: float | None) -> None:
    """The height map of `path` into the document's maps, and its height scale."""
    from core.map_io import MapFileError, fit_channels, read_image, resample

    t = document.terrain_spec
    scale = scale if scale is not None else (t.height_scale if t.height_scale > 0 else 10.0)
    if not 0.0 < scale <= 10_000.0:
        raise CliError(f"--height-scale {scale:g} out of range; above 0, at most 10000")
    values = None
    if path is not None:
        try:
            values = resample(fit_channels(read_image(path), "height", True), document.maps.size)
        except MapFileError as exc:
            raise CliError(f"--height-map: {exc}") from None
    document.set_heights(values, scale)


def cmd_render(args: argparse.Namespace) -> int:
    from core.params import PRESETS, ParameterError
    from render.headless import HeadlessRenderer

    document = _document(args)
    if (args.eye is None) != (args.target is None):
        raise CliError("--eye and --target go together")
    if args.out is None and args.stats is None:
        raise CliError("nothing to write: give --out PNG and/or --stats JSON")
    outs, kind = _frame_paths(args.out, len(args.time), args.size)
    for path in (*outs, args.stats):
        if path is not None:
            _writable(path)
    if args.density is not None and not 0.0 <= args.density <= 1.0:
        raise CliError(f"--density {args.density:g} out of range; allowed 0 … 1")

    params = document.params(0)
    if args.preset is not None:
        if args.preset not in PRESETS:
            raise CliError(f"unknown preset {args.preset!r}; presets: {', '.join(PRESETS)}")
        params = PRESETS[args.preset]
    try:
        if args.seed is not None:
            params = params.replace(seed=args.seed)
    except ParameterError as exc:
        raise CliError(f"--seed: {exc}") from None

    if args.eye is not None:
        try:
            from core.camera import Camera

            camera = Camera.from_eye_target(args.eye, args.target)
        except ValueError as exc:
            raise CliError(f"--eye/--target: {exc}") from None
        camera_name = "custom"
    else:
        camera_name = args.camera or document.default_camera
        _known_camera(document, camera_name)
        camera = document.camera(camera_name)

    document.set_params(0, params)
    if args.density is not None:
        document.density = args.density
    records, frames = [], []
    step = args.time[1] - args.time[0] if len(args.time) > 1 else 0.0
    video = _Video(outs[0], args.size, step) if kind == "mp4" else None
    try:
        with HeadlessRenderer(document, mode=args.only or "lod", view=args.view) as renderer:
            for index, seconds in enumerate(args.time):
                renderer.pipeline.time = seconds
                image, stats = renderer.render(camera, args.size, measure=True)
                records.append(
                    {**stats.to_dict(), "scene": document.name, "camera": camera_name,
                     "time": seconds}
                )  # fmt: skip
                if video is not None:
                    video.add(image)
                elif kind == "apng":
                    frames.append(image)
                elif outs:
                    _save_png(image, outs[index])
                    print(
                        f"wrote {outs[index]} ({args.size[0]}x{args.size[1]}, "
                        f"{stats.t_a_ms:.1f} ms)"
                    )
    finally:
        if video is not None:
            video.close()  # ffmpeg ends (on an error, with the frames drawn so far)
    if video is not None:
        print(f"wrote {outs[0]} ({len(records)} frames of {args.size[0]}x{args.size[1]}, video)")
    if kind == "apng":
        _save_animation(frames, outs[0], step)
        print(f"wrote {outs[0]} ({len(frames)} frames of {args.size[0]}x{args.size[1]}, animated)")
    if args.stats is not None:
        data = records[0] if len(records) == 1 else {"frames": records}
        try:
            args.stats.write_text(json.dumps(data, indent=2) + "\n")
        except OSError as exc:
            raise CliError(f"cannot write {args.stats}: {exc.strerror or exc}") from None
    return 0


ANIMATION_BYTES = 1 << 30  # the frames an animated PNG holds in memory before it is written


def _frame_paths(out: Path | None, count: int, size: tuple[int, int]) -> tuple[list[Path], str]:
    """Where the frames go, and how: --out itself for one frame ("png"); for a sequence its %d
    pattern filled in ("png"), an MP4 video for a .mp4 name ("mp4"), or else one animated PNG
    ("apng")."""
    if out is None:
        return [], "png"
    video = out.suffix.lower() == ".mp4"
    if count == 1:
        if video:
            raise CliError(f"--out {out}: a video needs a time sequence, e.g. --time 0:2:0.04")
        return [out], "png"
    if video:
        return [out], "mp4"
    if "%" not in str(out):
        need = count * size[0] * size[1] * 3
        if need > ANIMATION_BYTES:
            raise CliError(
                f"--out {out}: {count} frames of {size[0]}x{size[1]} are too many for one "
                f"animated PNG ({need / 2**30:.1f} GB in memory); give a pattern with %d, e.g. "
                "frames/f%04d.png, for a PNG a frame, or a .mp4 name for a video"
            )
        return [out], "apng"
    try:
        paths = [Path(str(out) % i) for i in range(count)]
    except (TypeError, ValueError):
        raise CliError(
            f"--out {out}: a time sequence needs one %d in the pattern, e.g. frames/f%04d.png"
        ) from None
    if len(set(paths)) != count:
        raise CliError(f"--out {out}: the pattern gives every frame the same name; use %04d")
    return paths, "png"


class _Video:
    """An H.264 MP4 written frame by frame through imageio-ffmpeg (its own ffmpeg binary):
    frames of odd width or height gain a copied last column or row (the codec's 4:2:0 colour
    needs even sizes)."""

    def __init__(self, path: Path, size: tuple[int, int], step_s: float) -> None:
        import imageio_ffmpeg

        self.path = path
        self.pad = (size[1] % 2, size[0] % 2)
        even = (size[0] + self.pad[1], size[1] + self.pad[0])
        self._writer = imageio_ffmpeg.write_frames(
            str(path), even, fps=1.0 / step_s, quality=8, macro_block_size=2
        )
        self._send(None)  # starts ffmpeg

    def _send(self, frame) -> None:
        try:
            self._writer.send(frame)
        except (OSError, RuntimeError) as exc:
            raise CliError(f"cannot write {self.path}: {exc}") from None

    def add(self, image) -> None:
        import numpy as np

        if any(self.pad):
            image = np.pad(image, ((0, self.pad[0]), (0, self.pad[1]), (0, 0)), mode="edge")
        self._send(np.ascontiguousarray(image))

    def close(self) -> None:
        try:
            self._writer.close()
        except (OSError, RuntimeError) as exc:
            raise CliError(f"cannot write {self.path}: {exc}") from None


def _save_animation(frames: list, path: Path, step_s: float) -> None:
    """An animated PNG (Pillow's APNG writer), each frame shown for the time step, looping."""
    from PIL import Image

    images = [Image.fromarray(f) for f in frames]
    try:
        images[0].save(
            path,
            format="PNG",
            save_all=True,
            append_images=images[1:],
            duration=max(round(step_s * 1000.0), 1),
            loop=0,
        )
    except OSError as exc:
        raise CliError(f"cannot write {path}: {exc.strerror or exc}") from None


def _save_png(image, path: Path) -> None:
    from PIL import Image

    try:
        Image.fromarray(image).save(path, format="PNG")
    except OSError as exc:
        raise CliError(f"cannot write {path}: {exc.strerror or exc}") from None


def cmd_profile(args: argparse.Namespace) -> int:
    from app.profile import profile

    document = _document(args)
    _known_path(document, args.path)
    frames = args.frames if args.frames is not None else (30 if args.path else 5)
    if not 1 <= frames <= 10_000:
        raise CliError(f"--frames {frames} out of range; allowed 1 … 10000")
    if args.out is not None:
        _writable(args.out)
    text, _ = profile(document, args.size, frames, args.path, args.out, args.only)
    print(text)
    return 0


def cmd_quality(args: argparse.Namespace) -> int:
    from app.quality import quality

    if args.sweep:
        return _sweep(args)
    if args.case:
        raise CliError("--case selects cases of --sweep; give --sweep as well")
    document = _document(args)
    for name in args.camera or []:
        _known_camera(document, name)
    _known_path(document, args.path)
    if not 2 <= args.frames <= 1000:
        raise CliError(f"--frames {args.frames} out of range; allowed 2 … 1000")
    if not args.budget > 0:
        raise CliError(f"--budget {args.budget:g} out of range; give seconds above 0")
    _out_folder(args.out, "quality.json")
    cameras = args.camera or ([] if args.path else [document.default_camera])
    if not (math.isfinite(args.time_step) and 0.0 <= args.time_step <= 3600.0):
        raise CliError(f"--time-step {args.time_step:g} out of range; 0 … 3600 seconds")
    if len(args.time) != 1:
        raise CliError("--time: sward quality takes one moment (SECONDS); --time-step moves it")
    text, _ = quality(
        document,
        args.size,
        cameras,
        args.path,
        args.frames,
        args.out,
        args.budget,
        args.time[0],
        args.time_step,
    )
    print(text)
    return 0


def _out_folder(out: Path | None, first: str) -> None:
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
    _writable(out / first)


def _sweep(args: argparse.Namespace) -> int:
    from app.sweep import cases, sweep

    if args.project is not None or args.camera or args.path:
        raise CliError(
            "--sweep draws the built-in scenes' cameras: drop --project, --camera, --path"
        )
    names = [case.name for case in cases()]
    for prefix in args.case or []:
        if not any(name.startswith(prefix) for name in names):
            raise CliError(f"--case {prefix}: no sweep case starts so; cases: {', '.join(names)}")
    _out_folder(args.out, "sweep.json")
    text, result = sweep(args.size, args.out, args.case)
    print(text)
    return 1 if result["failed"] else 0  # a guard: a check over its limit fails the run


def cmd_scenes(_: argparse.Namespace) -> int:
    from app.scenes import SCENES

    for scene in SCENES.values():
        print(f"{scene.name:12s} {scene.description}")
        print(f"{'':12s} cameras: {', '.join(scene.cameras)} (default {scene.default_camera})")
        if scene.paths:
            print(f"{'':12s} camera paths: {', '.join(scene.paths)}")
    return 0


def cmd_info(_: argparse.Namespace) -> int:
    from render import context

    ctx = context.standalone()
    print(f"OpenGL: {context.describe(ctx)}")
    ctx.release()
    return 0


def cmd_bench(args: argparse.Namespace) -> int:
    from app import bench

    return bench.run(args.suite, args.out)


def _program() -> str:
    """How the user reached this command: `.venv/bin/sward` when run by path, else `sward`."""
    argv0 = sys.argv[0]
    return argv0 if "/" in argv0 and Path(argv0).name == "sward" else "sward"


def _has_display() -> bool:
    return not sys.platform.startswith("linux") or bool(
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    )


def start_render_processes() -> None:
    """Start the designer's two render processes now, before the window's modules load: each
    imports its own and makes its GL context meanwhile (render/process_start.py). Only with
    the folder they share kept (render/derived_cache.py), where the window will find it."""
    from render import derived_cache, process_start

    folder = derived_cache.folder()
    if folder is not None and _has_display():
        process_start.start_early(process_start.ROLES, str(folder), derived_cache.SHARED_DIR_ENV)


def cmd_gui(_: argparse.Namespace) -> int:
    from app.scenes import DEFAULT_SCENE

    if not _has_display():
        print(
            "sward: no display found (DISPLAY is not set), so the designer cannot open.\n"
            "Render headless instead, e.g.:\n"
            f"  {_program()} render --scene {DEFAULT_SCENE} --out grass.png --stats stats.json",
            file=sys.stderr,
        )
        return 1
    from app.designer import run_designer

    return run_designer()


POINT_OPTIONS = ("--eye", "--target")


def _glue_points(argv: list[str]) -> list[str]:
    """`--eye -30,25,-30` as `--eye=-30,25,-30`: argparse takes a value that starts with a
    minus (and is not a plain number) for an option of its own."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        if argv[i] in POINT_OPTIONS and i + 1 < len(argv) and argv[i + 1].startswith("-"):
            out.append(f"{argv[i]}={argv[i + 1]}")
            i += 2
        else:
            out.append(argv[i])
            i += 1
    return out


def main(argv: list[str] | None = None) -> int:
    words = sys.argv[1:] if argv is None else argv
    if not words:  # the designer: its render processes start first
        start_render_processes()
    args = parser().parse_args(_glue_points(words))
    handler = {
        None: cmd_gui,
        "render": cmd_render,
        "scenes": cmd_scenes,
        "profile": cmd_profile,
        "new": cmd_new,
        "info": cmd_info,
        "bench": cmd_bench,
        "quality": cmd_quality,
    }[args.command]
    name = f"sward {args.command}" if args.command else "sward"
    try:
        return handler(args)
    except CliError as exc:
        print(f"{name}: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader went away (`sward profile ... | head`): stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # nothing left to flush
        return 141
    except Exception as exc:  # GL or environment failures: one line, no traceback
        from render.context import GLUnavailableError

        if isinstance(exc, GLUnavailableError):
            print(f"{name}: error: {exc}", file=sys.stderr)
            return 3
        raise


if __name__ == "__main__":
    sys.exit(main())
