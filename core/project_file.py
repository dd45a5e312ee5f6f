"""Project files: the document (core/document.py) in one zip file with a version number (format
described in docs/project-format.md) — project.json and maps.npz. One serialiser per type, each
a pair `_x` (to plain data) / `_x_from` (from it). Saving is atomic: the file is written beside
the old one and moved over it, so a crash mid-save leaves the old file.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import os
import stat
import tempfile
import time
import zipfile
import zlib
from pathlib import Path
from typing import Any

import msgspec
import numpy as np

from core import project_schema
from core.design_maps import FIRST_LAYERS, LAYERS, DesignMaps
from core.document import MAIN_GRASS, CameraSpec, Document, GrassType, Prop, TerrainSpec
from core.lighting import Lighting
from core.lod import LodConfig, LodLevel
from core.paint_rule import PaintRule
from core.params import ParameterError, PatchParams, SliceParams
from core.segments import TOLERANCE_PX
from core.species import Species
from core.wind import Wind

FORMAT = "sward-project"
VERSION = 1
SUFFIX = ".sward"
# the light a project keeps (the fog distance is its own entry; sky and soil are fixed)
LIGHT = "sun_elevation sun_azimuth sun_color ambient_color".split()
LIGHT += ["translucency", "blade_ao_impact", "blade_ao_height", "blade_shadows", "shadow_strength"]

MAX_FILE_BYTES = 4 << 30
MAX_JSON_BYTES = 16 << 20
MAX_MAP_SIDE = 4096  # a project's maps: at most 4096 × 4096 texels (1.3 GB of float32)
MAX_STACK_BYTES = len(LAYERS) * MAX_MAP_SIDE * MAX_MAP_SIDE * 4 * 4
# the largest value each map may hold (the smallest is 0)


class ProjectError(Exception):
    """A project file that cannot be read or written; the message names the file."""


# -- one serialiser per type -----------------------------------------------------------------
def _lod(config: LodConfig) -> dict:
    return {
        "levels": [dataclasses.asdict(level) for level in config.levels],
        "epsilon": config.epsilon,
        "silhouettes": config.silhouettes,
        "view_height": config.view_height,
        "segment_tolerance": config.segment_tolerance,
    }


def _lod_from(data: dict) -> LodConfig:
    return LodConfig(
        tuple(LodLevel(**level) for level in data["levels"]),
        data.get("epsilon", 0.05),
        data.get("silhouettes", False),
        data.get("view_height"),
        data.get("segment_tolerance", TOLERANCE_PX),
    )


def _camera(spec: CameraSpec) -> dict:
    return {"eye": list(spec.eye), "target": list(spec.target), "far": spec.far, "near": spec.near}


def _camera_from(data: dict) -> CameraSpec:
    return CameraSpec(
        _floats(data["eye"], 3), _floats(data["target"], 3), float(data["far"]), float(data["near"])
    )


def _prop(prop: Prop) -> list:
    row = [list(prop.position), list(prop.size), list(prop.color), prop.lift]
    return row if prop.shape == "box" else [*row, prop.shape]


def _prop_from(row: list) -> Prop:
    lift = float(row[3]) if len(row) > 3 else 0.0
    shape = str(row[4]) if len(row) > 4 else "box"
    return Prop(_floats(row[0], 2), _floats(row[1], 3), _floats(row[2], 3), lift, shape)


def _light(light: Lighting) -> dict:
    return {k: v for k, v in dataclasses.asdict(light).items() if k in LIGHT}


def _light_from(data: dict, fog_distance: float) -> Lighting:
    unknown = set(data) - set(LIGHT)
    if unknown:
        raise ValueError(f"unknown light setting {sorted(unknown)[0]!r}")
    values: dict[str, Any] = {
        k: tuple(v) if isinstance(v, list | tuple) else v if isinstance(v, bool) else float(v)
        for k, v in data.items()
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
        "wind": doc.wind.to_dict(),
        "species": doc.species.to_dict(),
        "paint_rule": doc.paint_rule.to_dict(),
    }


def document_from_data(data: dict, stack: np.ndarray, copy: bool = True) -> Document:
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
        DesignMaps.from_stack(stack, copy=copy),
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
        wind=Wind.from_dict(data.get("wind", {})),
        species=Species.from_dict(data.get("species", {})),
        paint_rule=PaintRule.from_dict(data.get("paint_rule", {})),
    )


# -- files -----------------------------------------------------------------------------------
def save_project(path: Path | str, doc: Document) -> None:
    """Write the document and its maps to `path`, atomically and durably: a temporary file
    beside the target, flushed to disk, renamed over it, the folder flushed too. Saving through
    a symbolic link writes the file it points to; temporary files an earlier crash left behind
    are removed."""
    path = Path(path)
    target = Path(os.path.realpath(path))  # through a link: its target, not the link
    try:
        text = json.dumps(document_data(doc), indent=2)
        buffer = io.BytesIO()
        np.savez_compressed(buffer, stack=doc.maps.stack)
        folder = target.parent
        _remove_stale_temporaries(target)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=folder)
        try:
            with os.fdopen(fd, "wb") as raw:
                with zipfile.ZipFile(raw, "w") as z:
                    z.writestr("project.json", text)
                    z.writestr("maps.npz", buffer.getvalue())
                raw.flush()
                os.fsync(raw.fileno())
            os.chmod(tmp, _mode(target))
            os.replace(tmp, target)
            _fsync_folder(folder)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    except (OSError, TypeError, ValueError) as exc:
        raise ProjectError(f"cannot save {path}: {exc}") from None


STALE_S = 60.0  # a temporary file this old belongs to no save in progress


def _remove_stale_temporaries(target: Path) -> None:
    now = time.time()
    for old in target.parent.glob(f".{target.name}.*.tmp"):
        with contextlib.suppress(OSError):
            if now - old.stat().st_mtime > STALE_S:
                old.unlink()


def _fsync_folder(folder: Path) -> None:
    fd = os.open(folder, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _mode(path: Path) -> int:
    """The file mode to keep: the old file's, or what the umask allows for a new one."""
    if path.exists():
        return path.stat().st_mode & 0o777
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def load_project(path: Path | str) -> Document:
    """The document stored in `path`. A file that is not a readable, valid project of a known
    version raises ProjectError naming the file, the field and the rule; reading is bounded in
    time and memory (only regular files, member sizes checked before inflating, the maps' array
    header before allocating, the maps read once into their own array)."""
    path = Path(path)
    try:
        return _load(path)
    except ProjectError:
        raise
    except FileNotFoundError:
        raise ProjectError(f"cannot open {path}: no such file") from None
    except PermissionError:
        raise ProjectError(f"cannot open {path}: permission denied") from None
    except zipfile.BadZipFile:
        raise ProjectError(f"cannot open {path}: not a Sward project (not a zip file)") from None
    except (msgspec.ValidationError, msgspec.DecodeError) as exc:
        raise ProjectError(f"cannot open {path}: project.json: {_rule(exc)}") from None
    except (ParameterError, ValueError, TypeError, KeyError, OverflowError) as exc:
        raise ProjectError(f"cannot open {path}: {exc}") from None
    except (OSError, EOFError, RuntimeError, NotImplementedError, zlib.error, MemoryError) as exc:
        raise ProjectError(f"cannot open {path}: damaged ({type(exc).__name__}: {exc})") from None


def _rule(exc: Exception) -> str:
    """msgspec's message with the field first: `terrain.columns: Expected int <= 16384`."""
    text = str(exc)
    if " - at `$." in text:
        rule, where = text.rsplit(" - at `$.", 1)
        return f"{where.rstrip('`')}: {rule[0].lower()}{rule[1:]}"
    return text


def _load(path: Path) -> Document:
    info = os.stat(path)  # follows a link: its target must be a regular file too
    if not stat.S_ISREG(info.st_mode):
        raise ProjectError(f"cannot open {path}: not a regular file")
    if info.st_size > MAX_FILE_BYTES:
        raise ProjectError(f"cannot open {path}: larger than {MAX_FILE_BYTES >> 30} GiB")
    with zipfile.ZipFile(path) as z:
        raw = _member(z, "project.json", MAX_JSON_BYTES, path)
        head = project_schema.head(raw)
        if head.format != FORMAT:
            raise ProjectError(f"cannot open {path}: not a Sward project")
        if head.version != VERSION:
            raise ProjectError(
                f"cannot open {path}: project format version {head.version!r}; "
                f"this Sward reads version {VERSION}"
            )
        project = project_schema.decode(raw)
        stack = _maps(z, path)
    document = document_from_data(msgspec.to_builtins(project), stack, copy=False)
    return document


def _member(z: zipfile.ZipFile, name: str, limit: int, path: Path) -> bytes:
    try:
        info = z.getinfo(name)
    except KeyError:
        raise ProjectError(f"cannot open {path}: it lacks {name}") from None
    _check_member(info, limit, path)
    return z.read(info)


def _check_member(info: zipfile.ZipInfo, limit: int, path: Path) -> None:
    name = info.filename
    if info.flag_bits & 0x1:
        raise ProjectError(f"cannot open {path}: {name} is encrypted")
    if info.compress_type not in (zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED):
        raise ProjectError(f"cannot open {path}: {name} uses an unsupported compression")
    if info.file_size > limit:
        raise ProjectError(
            f"cannot open {path}: {name} would inflate to {info.file_size:,} bytes "
            f"(at most {limit:,})"
        )


def _maps(z: zipfile.ZipFile, path: Path) -> np.ndarray:
    """maps.npz's `stack`: its header checked, then read once into its own array."""
    outer = _member(z, "maps.npz", MAX_STACK_BYTES + 65536, path)
    if not outer.startswith(b"PK"):
        raise ProjectError(f"cannot open {path}: maps.npz is not an npz archive")
    with zipfile.ZipFile(io.BytesIO(outer)) as inner:
        try:
            info = inner.getinfo("stack.npy")
        except KeyError:
            raise ProjectError(f"cannot open {path}: maps.npz lacks the array 'stack'") from None
        _check_member(info, MAX_STACK_BYTES + 4096, path)
        with inner.open(info) as f:
            version = np.lib.format.read_magic(f)
            if version == (1, 0):
                shape, fortran, dtype = np.lib.format.read_array_header_1_0(f)
            elif version == (2, 0):
                shape, fortran, dtype = np.lib.format.read_array_header_2_0(f)
            else:
                raise ProjectError(f"cannot open {path}: maps.npz: unknown .npy version")
            _check_stack_header(shape, fortran, dtype, path)
            # a file from before trampled grass holds the first layers: the rest take their
            # defaults (nothing trampled)
            stack = np.empty((len(LAYERS), *shape[1:]), np.float32)
            if _read_into(f, stack[: shape[0]]) != stack[: shape[0]].nbytes:
                raise ProjectError(f"cannot open {path}: maps.npz: the maps are truncated")
            for i in range(shape[0], len(LAYERS)):
                stack[i] = LAYERS[i].default
    _check_stack_values(stack, path)
    return stack


def _read_into(f: Any, array: np.ndarray) -> int:
    """Fill `array` from the stream in chunks: the only copy of the maps is the array itself."""
    view = memoryview(array.reshape(-1).view(np.uint8))  # type: ignore[arg-type]
    done = 0
    while done < len(view):
        n = f.readinto(view[done : done + (64 << 20)])
        if not n:
            break
        done += n
    return done


def _check_stack_header(shape, fortran: bool, dtype, path: Path) -> None:
    layers = len(LAYERS)
    ok = (
        len(shape) == 4
        and shape[0] in (FIRST_LAYERS, layers)
        and shape[3] == 4
        and 1 <= shape[1] <= MAX_MAP_SIDE
        and 1 <= shape[2] <= MAX_MAP_SIDE
    )
    if not ok:
        raise ProjectError(
            f"cannot open {path}: maps.npz: the stack must be ({layers}, rows, columns, 4) with "
            f"rows and columns 1 … {MAX_MAP_SIDE}, got {tuple(shape)}"
        )
    if np.dtype(dtype) != np.dtype("<f4") or fortran:
        raise ProjectError(f"cannot open {path}: maps.npz: the stack must be float32, got {dtype}")


def _check_stack_values(stack: np.ndarray, path: Path) -> None:
    """Every map within its range (NaN and infinity fail both tests)."""
    for i, layer in enumerate(LAYERS):
        values = stack[i, :, :, : layer.channels]
        low, high = float(values.min()), float(values.max())
        top = layer.top
        if not (0.0 <= low and high <= top):
            raise ProjectError(
                f"cannot open {path}: maps.npz: the {layer.name} map must hold numbers in "
                f"0 … {top:g}, found {low:g} … {high:g}"
            )
