"""`sward export`: its options, their checks and its report."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from app.cli_input import CliError, document_of, out_folder


def export_options(e: argparse.ArgumentParser) -> None:
    from app.export import WHAT

    e.add_argument("--out", type=Path, required=True, help="folder to write the export into")
    e.add_argument(
        "--format", choices=("gltf",), default="gltf", help="glTF 2.0 with instancing (default)"
    )
    e.add_argument(
        "--what",
        default=",".join(WHAT),
        help=f"what to write, comma-separated: {','.join(WHAT)} (default: all)",
    )


def cmd_export(args: argparse.Namespace) -> int:
    from app.export import WHAT, ExportError, export

    what = tuple(w.strip() for w in args.what.split(",") if w.strip())
    unknown = [w for w in what if w not in WHAT]
    if unknown or not what:
        raise CliError(
            f"--what {args.what}: {', '.join(unknown) or 'nothing'} is not one of {','.join(WHAT)}"
        )
    document = document_of(args)
    out_folder(args.out, "grass.gltf")
    start = time.monotonic()
    try:
        written = export(document, args.out, what, say=print)
    except ExportError as exc:
        raise CliError(str(exc)) from None
    gltf = written.get("gltf")
    if gltf is not None:
        per_type = ", ".join(f"{n} {c}" for n, c in gltf["instances"].items())
        print(
            f"{args.out / 'grass.gltf'}: {len(gltf['vertices'])} patch meshes"
            + (f", instances {per_type} in {gltf['blocks']} blocks" if per_type else "")
            + (f", terrain {gltf['ground_vertices']} vertices" if "ground_vertices" in gltf else "")
            + f", {gltf['bytes'] / 2**20:.1f} MB of buffer"
        )
    if "maps" in written:
        print(f"{args.out / 'maps'}: {len(written['maps'])} files")
    if "settings" in written:
        print(f"{args.out / 'settings.json'}: grass types, LOD levels, light, terrain")
    print(f"exported in {time.monotonic() - start:.1f} s")
    return 0
