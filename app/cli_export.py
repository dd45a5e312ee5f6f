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
        "--format",
        choices=("gltf", "usd"),
        default="gltf",
        help="glTF 2.0 with instancing (default) or USD point instancers (sward[usd])",
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
        written = export(document, args.out, what, say=print, format=args.format)
    except ExportError as exc:
        raise CliError(str(exc)) from None
    meshes = written.get("gltf") or written.get("usd")
    if meshes is not None:
        name = "grass.gltf" if "gltf" in written else "grass.usda"
        per_type = ", ".join(f"{n} {c}" for n, c in meshes["instances"].items())
        print(
            f"{args.out / name}: {len(meshes['vertices'])} patch meshes"
            + (f", instances {per_type} in {meshes['blocks']} blocks" if per_type else "")
            + (
                f", terrain {meshes['ground_vertices']} vertices"
                if "ground_vertices" in meshes
                else ""
            )
            + (f", {meshes['bytes'] / 2**20:.1f} MB of buffer" if "bytes" in meshes else "")
        )
    if "slices" in written:
        print(f"{args.out / 'slices'}: {', '.join(written['slices'].values())}")
    if "maps" in written:
        print(f"{args.out / 'maps'}: {len(written['maps'])} files")
    if "settings" in written:
        print(f"{args.out / 'settings.json'}: grass types, LOD levels, light, terrain")
    print(f"exported in {time.monotonic() - start:.1f} s")
    return 0
