"""`sward tune`: its options, their checks, the search's start and --apply."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

from app.cli_input import CliError, _size, document_of, known_camera, known_path, out_folder


def tune_options(t: argparse.ArgumentParser) -> None:
    t.add_argument("--camera", action="append", help="named camera (repeat for several)")
    t.add_argument("--path", help="camera path: its frames are the views, popping counts too")
    t.add_argument("--frames", type=int, default=6, help="frames along --path (default 6)")
    target = t.add_mutually_exclusive_group()
    target.add_argument(
        "--budget-ms",
        type=float,
        help="frame time to stay within (default: the shipped setting's, measured)",
    )
    target.add_argument("--quality", type=float, help="quarter-resolution FLIP to reach")
    t.add_argument("--size", type=_size, default=(480, 270), help="image size WxH")
    t.add_argument(
        "--candidates", type=int, default=150, help="settings to try at most (default 150)"
    )
    t.add_argument("--out", type=Path, help="folder for tune.json and front.png")
    t.add_argument(
        "--apply", action="store_true", help="write the chosen setting into --project's file"
    )
    where = t.add_mutually_exclusive_group()
    where.add_argument(
        "--workers", type=int, help="draw in N processes of this machine (costs predicted)"
    )
    where.add_argument(
        "--ray", metavar="ADDRESS", help="draw on the Ray cluster at ADDRESS (sward[cluster])"
    )


def cmd_tune(args: argparse.Namespace) -> int:
    from app.tune import tune

    document = document_of(args)
    for name in args.camera or []:
        known_camera(document, name)
    known_path(document, args.path)
    if args.path is not None and args.camera:
        raise CliError("give --camera or --path, not both")
    if not 2 <= args.frames <= 100:
        raise CliError(f"--frames {args.frames} out of range; allowed 2 … 100")
    if args.budget_ms is not None and not 0 < args.budget_ms <= 1e6:
        raise CliError(f"--budget-ms {args.budget_ms:g} out of range; above 0")
    if args.quality is not None and not 0 < args.quality < 1:
        raise CliError(f"--quality {args.quality:g} out of range; a FLIP above 0, below 1")
    if not 1 <= args.candidates <= 10_000:
        raise CliError(f"--candidates {args.candidates} out of range; allowed 1 … 10000")
    if args.workers is not None and not 1 <= args.workers <= 256:
        raise CliError(f"--workers {args.workers} out of range; allowed 1 … 256")
    if args.apply and args.project is None:
        raise CliError("--apply writes into a project file: give --project FILE")
    out_folder(args.out, "tune.json")
    if args.path is not None:
        views = [(f"path {args.path}", document.path_cameras(args.path, args.frames))]
    else:
        from app.tune_run import dolly

        names = args.camera or [document.default_camera]
        views = [(n, dolly(document.camera(n))) for n in names]
    text, result = tune(
        document,
        args.size,
        views,
        args.path,
        args.budget_ms,
        args.quality,
        args.out,
        max_candidates=args.candidates,
        workers=_workers(args),
    )
    print(text)
    if args.apply:
        _apply_tuned(args.project, result)
    return 0


def _apply_tuned(path: Path, result: dict) -> None:
    """The chosen knobs turned on the project file's own levels, and only those: what the
    command line overrode for the run (--wind, --lod-view-height) stays as the file has it.
    One edit: the file is written once."""
    from core.project_file import ProjectError, load_project, save_project
    from core.tuning import Knobs, tuned

    if result["chosen"] is None:
        print(f"{path} left as it was: nothing tried meets the target")
        return
    knobs = Knobs(**result["candidates"][result["chosen"]]["knobs"])
    try:
        project = load_project(path)
        project.set_lods([tuned(lod, knobs) for lod in project.lods])  # type: ignore[misc]
        save_project(path, project)
    except ProjectError as exc:
        raise CliError(str(exc)) from None
    print(f"wrote the chosen LOD setting into {path}")


def _workers(args: argparse.Namespace) -> Callable | None:
    """What starts the pool of --workers or --ray, or None: draw here."""
    from app.tune_workers import ClusterError, local_pool, ray_pool

    if args.workers is not None:
        count = args.workers
        return lambda setup: local_pool(count, setup)
    if args.ray is not None:
        address = args.ray

        def start(setup: tuple):
            try:
                return ray_pool(address, setup)
            except ClusterError as exc:
                raise CliError(str(exc)) from None

        return start
    return None
