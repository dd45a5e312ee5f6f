"""Project files: the document (core/document.py) in one zip file with a version number (format
described in docs/project-format.md) — project.json and maps.npz. One serialiser per type, each
a pair `_x` (to plain data) / `_x_from` (from it). Saving is atomic: the file is written beside
the old one and moved over it, so a crash mid-save leaves the old file.
"""

from __future__ import annotations

import dataclasses
import io
import json
import os
import tempfile
import zipfile
from pathlib import Path
from typing import Any

import numpy as np

from core.design_maps import DesignMaps
from core.document import MAIN_GRASS, CameraSpec, Document, GrassType, Prop, TerrainSpec
from core.lighting import Lighting
from core.lod import LodConfig, LodLevel
from core.params import ParameterError, PatchParams, SliceParams

FORMAT = "sward-project"
VERSION = 1
SUFFIX = ".sward"
# the light a project keeps (the fog distance is its own entry; sky and soil are fixed)
LIGHT = (
    "sun_elevation",
    "sun_azimuth",
    "sun_color",
    "ambient_color",
    "translucency",
    "blade_ao_impact",
    "blade_ao_height",
)


class ProjectError(Exception):
    """A project file that cannot be read or written; the message names the file."""


# -- one serialiser per type -----------------------------------------------------------------
def _lod(config: LodConfig) -> dict:
    return {
        "levels": [dataclasses.asdict(level) for level in config.levels],
        "epsilon": config.epsilon,
        "silhouettes": config.silhouettes,
    }


def _lod_from(data: dict) -> LodConfig:
    return LodConfig(
        tuple(LodLevel(**level) for level in data["levels"]),
        data.get("epsilon", 0.05),
        data.get("silhouettes", False),
    )


def _camera(spec: CameraSpec) -> dict:
    return {"eye": list(spec.eye), "target": list(spec.target), "far": spec.far, "near": spec.near}


def _camera_from(data: dict) -> CameraSpec:
    return CameraSpec(
        _floats(data["eye"], 3), _floats(data["target"], 3), float(data["far"]), float(data["near"])
    )


def _prop(prop: Prop) -> list:
    return [list(prop.position), list(prop.size), list(prop.color), prop.lift]


def _prop_from(row: list) -> Prop:
    return Prop(_floats(row[0], 2), _floats(row[1], 3), _floats(row[2], 3), float(*row[3:4] or [0]))


def _light(light: Lighting) -> dict:
    return {k: v for k, v in dataclasses.asdict(light).items() if k in LIGHT}


def _light_from(data: dict, fog_distance: float) -> Lighting:
    unknown = set(data) - set(LIGHT)
    if unknown:
        raise ValueError(f"unknown light setting {sorted(unknown)[0]!r}")
    values: dict[str, Any] = {
        k: tuple(v) if isinstance(v, list | tuple) else float(v) for k, v in data.items()
    }
    return Lighting(**values, fog_distance=fog_distance)


def _floats(values, n: int) -> tuple:
    out = tuple(float(v) for v in values)
    if len(out) != n:
        raise ValueError(f"expected {n} numbers, got {len(out)}")
    return out


def document_data(doc: Document) -> dict:
    """The document as the JSON of a project file (the maps go beside it)."""
    first, *further = doc.grass_types
    t = doc.terrain_spec
    return {
        "format": FORMAT,
        "version": VERSION,
        "name": doc.name,
        "description": doc.description,
        "params": first.params.to_dict(),
        "density": doc.density,
        "terrain": {
            "columns": t.columns,
            "rows": t.rows,
            "mirror_seed": t.mirror_seed,
            "height_scale": t.height_scale,
        },
        "lod": _lod(first.lod),
        "grass": [
            {
                "name": kind.name,
                "params": kind.params.to_dict(),
                "lod": _lod(kind.lod),
                "channel": kind.channel,
            }
            for kind in further
        ],
        "cameras": {name: _camera(spec) for name, spec in doc.cameras.items()},
        "default_camera": doc.default_camera,
        "paths": {name: [_camera(k) for k in keys] for name, keys in doc.paths.items()},
        "props": [_prop(p) for p in doc.props],
        "fog_distance": doc.light.fog_distance,
        "light": _light(doc.light),
        "slices": dataclasses.asdict(doc.slices),
    }


def document_from_data(data: dict, stack: np.ndarray) -> Document:
    terrain = data["terrain"]
    grass = [GrassType(MAIN_GRASS, PatchParams.from_dict(data["params"]), _lod_from(data["lod"]))]
    for g in data.get("grass", []):
        params = PatchParams.from_dict(g["params"])
        grass.append(GrassType(str(g["name"]), params, _lod_from(g["lod"]), int(g["channel"])))
    return Document(
        str(data["name"]),
        grass,
        TerrainSpec(
            int(terrain["columns"]),
            int(terrain["rows"]),
            terrain.get("mirror_seed"),
            float(terrain.get("height_scale", 0.0)),
        ),
        DesignMaps.from_stack(stack),
        description=str(data.get("description", "")),
        density=float(data.get("density", 1.0)),
        slices=SliceParams(**data.get("slices", {})),
        light=_light_from(data.get("light", {}), float(data.get("fog_distance", 160.0))),
        cameras={name: _camera_from(c) for name, c in data["cameras"].items()},
        default_camera=data["default_camera"],
        paths={
            name: tuple(_camera_from(k) for k in keys)
            for name, keys in data.get("paths", {}).items()
        },
        props=tuple(_prop_from(row) for row in data.get("props", [])),
    )


# -- files -----------------------------------------------------------------------------------
def save_project(path: Path | str, doc: Document) -> None:
    """Write the document and its maps to `path`, atomically."""
    path = Path(path)
    try:
        text = json.dumps(document_data(doc), indent=2)
        buffer = io.BytesIO()
        np.savez_compressed(buffer, stack=doc.maps.stack)
        folder = path.resolve().parent
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
        try:
            with os.fdopen(fd, "wb") as raw, zipfile.ZipFile(raw, "w") as z:
                z.writestr("project.json", text)
                z.writestr("maps.npz", buffer.getvalue())
            os.chmod(tmp, _mode(path))
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    except (OSError, TypeError, ValueError) as exc:
        raise ProjectError(f"cannot save {path}: {exc}") from None


def _mode(path: Path) -> int:
    """The file mode to keep: the old file's, or what the umask allows for a new one."""
    if path.exists():
        return path.stat().st_mode & 0o777
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def load_project(path: Path | str) -> Document:
    """The document stored in `path`; a file that is not a readable project of a known version
    raises ProjectError naming the file and the reason."""
    path = Path(path)
    try:
        with zipfile.ZipFile(path) as z:
            data = json.loads(z.read("project.json"))
            with np.load(io.BytesIO(z.read("maps.npz"))) as arrays:
                stack = np.array(arrays["stack"], np.float32)
    except FileNotFoundError:
        raise ProjectError(f"cannot open {path}: no such file") from None
    except zipfile.BadZipFile:
        raise ProjectError(f"cannot open {path}: not a Sward project (not a zip file)") from None
    except KeyError as exc:
        raise ProjectError(f"cannot open {path}: it lacks {exc.args[0]}") from None
    except (OSError, ValueError, EOFError) as exc:
        raise ProjectError(f"cannot open {path}: damaged ({exc})") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise ProjectError(f"cannot open {path}: not a Sward project")
    if data.get("version") != VERSION:
        raise ProjectError(
            f"cannot open {path}: project format version {data.get('version')!r}; "
            f"this Sward reads version {VERSION}"
        )
    try:
        return document_from_data(data, stack)
    except (KeyError, TypeError) as exc:
        raise ProjectError(f"cannot open {path}: missing or malformed entry {exc}") from None
    except (ParameterError, ValueError) as exc:
        raise ProjectError(f"cannot open {path}: {exc}") from None
