"""The `sward` command line (the contract in DESIGN.md): one function a command; the parser
and the input it checks are in app/cli_input.py, `sward render` in app/cli_render.py."""

from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

from app.cli_export import cmd_export
from app.cli_input import (
    CliError,
    document_of,
    known_camera,
    known_path,
    out_folder,
    overrides,
    parser,
    writable,
)
from app.cli_render import cmd_render
from app.cli_tune import cmd_tune


def cmd_new(args: argparse.Namespace) -> int:
    from core.project_file import ProjectError, save_project

    if args.cells is None:
        document = document_of(args)
    else:
        from app.scenes import get_scene

        try:
            document = get_scene(args.scene).resized(*args.cells).document()
        except KeyError as exc:
            raise CliError(exc.args[0]) from None
        except ValueError as exc:
            raise CliError(f"--cells: {exc}") from None
        overrides(document, args)
    if args.height_map is not None or args.height_scale is not None:
        _import_heights(document, args.height_map, args.height_scale)
    if args.species_map is not None:
        from core.map_io import MapFileError, fit_channels, read_image_at
        from core.species import density_layer

        try:
            rgb = fit_channels(
                read_image_at(args.species_map, document.maps.size)[0], "ambient", False
            )
        except MapFileError as exc:
            raise CliError(f"--species-map: {exc}") from None
        document.maps.write("density", 0, 0, density_layer(document, rgb))
    writable(args.file)
    try:
        save_project(args.file, document)
    except ProjectError as exc:
        raise CliError(str(exc)) from None
    t = document.terrain_spec
    print(f"wrote {args.file} (scene {document.name}, {t.columns} × {t.rows} cells)")
    return 0


def _import_heights(document, path: Path | None, scale: float | None) -> None:
    """The height map of `path` into the document's maps, and its height scale."""
    from core.map_io import MapFileError, fit_channels, read_image_at

    t = document.terrain_spec
    scale = scale if scale is not None else (t.height_scale if t.height_scale > 0 else 10.0)
    if not 0.0 < scale <= 10_000.0:
        raise CliError(f"--height-scale {scale:g} out of range; above 0, at most 10000")
    values = None
    if path is not None:
        try:
            values = fit_channels(read_image_at(path, document.maps.size)[0], "height", True)
        except MapFileError as exc:
            raise CliError(f"--height-map: {exc}") from None
    document.set_heights(values, scale)


def cmd_profile(args: argparse.Namespace) -> int:
    from app.profile import profile

    document = document_of(args)
    known_path(document, args.path)
    frames = args.frames if args.frames is not None else (30 if args.path else 5)
    if not 1 <= frames <= 10_000:
        raise CliError(f"--frames {frames} out of range; allowed 1 … 10000")
    if args.out is not None:
        writable(args.out)
    if args.hold_ms is not None:
        if args.path is None:
            raise CliError("--hold-ms follows a camera path: give --path NAME")
        if not 0 < args.hold_ms <= 1e6:
            raise CliError(f"--hold-ms {args.hold_ms:g} out of range; above 0")
        from app.hold import hold

        text, _ = hold(document, args.size, args.path, frames, args.hold_ms, args.out)
        print(text)
        return 0
    text, _ = profile(document, args.size, frames, args.path, args.out, args.only)
    print(text)
    return 0


def cmd_quality(args: argparse.Namespace) -> int:
    from app.quality import quality

    if args.sweep:
        return _sweep(args)
    if args.case:
        raise CliError("--case selects cases of --sweep; give --sweep as well")
    document = document_of(args)
    for name in args.camera or []:
        known_camera(document, name)
    known_path(document, args.path)
    if not 2 <= args.frames <= 1000:
        raise CliError(f"--frames {args.frames} out of range; allowed 2 … 1000")
    if not args.budget > 0:
        raise CliError(f"--budget {args.budget:g} out of range; give seconds above 0")
    out_folder(args.out, "quality.json")
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
    out_folder(args.out, "sweep.json")
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
        "tune": cmd_tune,
        "export": cmd_export,
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
