"""Project files: a scene as a person set it up — patch parameters per grass type, LOD levels,
slices, light, cameras, camera paths, props, terrain, and the painted design maps — in one zip
file with a version number (format described in docs/project-format.md). Saving is atomic: the
file is written beside the old one and moved over it, so a crash mid-save leaves the old file.
"""

from __future__ import annotations

import dataclasses
import io
import json
import os
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from app.scenes import CameraSpec, GrassType, Scene
from core.design_maps import DesignMaps
from core.lighting import Lighting
from core.lod import LodConfig, LodLevel
from core.params import ParameterError, PatchParams, SliceParams

FORMAT = "sward-project"
VERSION = 1
SUFFIX = ".sward"


class ProjectError(Exception):
    """A project file that cannot be read or written; the message names the file."""


# -- to and from plain data ------------------------------------------------------------------
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


def _params(params: PatchParams) -> dict:
    return dataclasses.asdict(params)


def _params_from(data: dict) -> PatchParams:
    known = {f.name for f in dataclasses.fields(PatchParams)}
    unknown = set(data) - known
    if unknown:
        raise ValueError(f"unknown patch parameter {sorted(unknown)[0]!r}")
    values = {k: tuple(v) if isinstance(v, list) else v for k, v in data.items()}
    return PatchParams(**values)


def _camera(spec: CameraSpec) -> dict:
    return {"eye": list(spec.eye), "target": list(spec.target), "far": spec.far, "near": spec.near}


def _camera_from(data: dict) -> CameraSpec:
    return CameraSpec(tuple(data["eye"]), tuple(data["target"]), data["far"], data["near"])


def scene_document(scene: Scene) -> dict:
    return {
        "format": FORMAT,
        "version": VERSION,
        "name": scene.name,
        "description": scene.description,
        "params": _params(scene.params),
        "density": scene.density,
        "terrain": {
            "columns": scene.grid[0],
            "rows": scene.grid[1],
            "mirror_seed": scene.mirror_seed,
            "height_scale": scene.height_scale,
        },
        "lod": _lod(scene.lod),
        "grass": [
            {
                "name": kind.name,
                "params": _params(kind.params),
                "lod": _lod(kind.lod),
                "channel": kind.channel,
            }
            for kind in scene.grass
        ],
        "cameras": {name: _camera(spec) for name, spec in scene.cameras.items()},
        "default_camera": scene.default_camera,
        "paths": {name: [_camera(k) for k in keys] for name, keys in scene.paths.items()},
        "props": [
            [list(row[0]), list(row[1]), list(row[2]), *(row[3:] or [])] for row in scene.props
        ],
        "fog_distance": scene.fog_distance,
        "light": {k: v for k, v in dataclasses.asdict(scene.lighting).items() if k in LIGHT},
        "slices": dataclasses.asdict(scene.slices),
    }


def scene_from_document(doc: dict, stack: np.ndarray) -> Scene:
    terrain = doc["terrain"]
    return Scene(
        name=doc["name"],
        description=doc.get("description", ""),
        params=_params_from(doc["params"]),
        grid=(int(terrain["columns"]), int(terrain["rows"])),
        density=float(doc.get("density", 1.0)),
        cameras={name: _camera_from(c) for name, c in doc["cameras"].items()},
        default_camera=doc["default_camera"],
        lod=_lod_from(doc["lod"]),
        mirror_seed=terrain.get("mirror_seed"),
        map_size=(stack.shape[2], stack.shape[1]),
        props=tuple((tuple(r[0]), tuple(r[1]), tuple(r[2]), *r[3:]) for r in doc.get("props", [])),
        fog_distance=float(doc.get("fog_distance", 160.0)),
        paths={
            name: tuple(_camera_from(k) for k in keys)
            for name, keys in doc.get("paths", {}).items()
        },
        height_scale=float(terrain.get("height_scale", 0.0)),
        grass=tuple(
            GrassType(g["name"], _params_from(g["params"]), _lod_from(g["lod"]), int(g["channel"]))
            for g in doc.get("grass", [])
        ),
        stack=stack,
        slices=SliceParams(**doc.get("slices", {})),
        lighting=_light_from(doc.get("light", {})),
    )


LIGHT = (
    "sun_elevation",
    "sun_azimuth",
    "sun_color",
    "ambient_color",
    "translucency",
    "blade_ao_impact",
    "blade_ao_height",
)


def _light_from(data: dict) -> Lighting:
    unknown = set(data) - set(LIGHT)
    if unknown:
        raise ValueError(f"unknown light setting {sorted(unknown)[0]!r}")
    values = {k: tuple(v) if isinstance(v, list) else float(v) for k, v in data.items()}
    return Lighting(**values)


# -- files -----------------------------------------------------------------------------------
def save_project(path: Path, scene: Scene, maps: DesignMaps | None = None) -> None:
    """Write `scene` and its maps (by default the scene's own) to `path`, atomically."""
    path = Path(path)
    maps = maps or scene.design_maps()
    try:
        doc = json.dumps(scene_document(scene), indent=2)
        buffer = io.BytesIO()
        np.savez_compressed(buffer, stack=maps.stack)
        folder = path.resolve().parent
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
        try:
            with os.fdopen(fd, "wb") as raw, zipfile.ZipFile(raw, "w") as z:
                z.writestr("project.json", doc)
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


def load_project(path: Path) -> Scene:
    """The scene stored in `path`; a file that is not a readable project of a known version
    raises ProjectError naming the file and the reason."""
    path = Path(path)
    try:
        with zipfile.ZipFile(path) as z:
            doc = json.loads(z.read("project.json"))
            with np.load(io.BytesIO(z.read("maps.npz"))) as data:
                stack = np.array(data["stack"], np.float32)
    except FileNotFoundError:
        raise ProjectError(f"cannot open {path}: no such file") from None
    except zipfile.BadZipFile:
        raise ProjectError(f"cannot open {path}: not a Sward project (not a zip file)") from None
    except KeyError as exc:
        raise ProjectError(f"cannot open {path}: it lacks {exc.args[0]}") from None
    except (OSError, ValueError, EOFError) as exc:
        raise ProjectError(f"cannot open {path}: damaged ({exc})") from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise ProjectError(f"cannot open {path}: not a Sward project")
    if doc.get("version") != VERSION:
        raise ProjectError(
            f"cannot open {path}: project format version {doc.get('version')!r}; "
            f"this Sward reads version {VERSION}"
        )
    try:
        DesignMaps.from_stack(stack)
        return scene_from_document(doc, stack)
    except (KeyError, TypeError) as exc:
        raise ProjectError(f"cannot open {path}: missing or malformed entry {exc}") from None
    except (ParameterError, ValueError) as exc:
        raise ProjectError(f"cannot open {path}: {exc}") from None
