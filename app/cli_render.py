"""`sward render`: one frame, or a sequence of the wind's moments, headless to PNG, an animated
PNG or an MP4 video, with the frame statistics as JSON."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from app.cli_input import CliError, document_of, known_camera, writable


def cmd_render(args: argparse.Namespace) -> int:
    from core.params import PRESETS, ParameterError
    from render.headless import HeadlessRenderer

    document = document_of(args)
    if (args.eye is None) != (args.target is None):
        raise CliError("--eye and --target go together")
    if args.out is None and args.stats is None:
        raise CliError("nothing to write: give --out PNG and/or --stats JSON")
    outs, kind = _frame_paths(args.out, len(args.time), args.size)
    for path in (*outs, args.stats):
        if path is not None:
            writable(path)
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
        known_camera(document, camera_name)
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
