"""Design maps to and from files (map import and export): PNG 8- and 16-bit greyscale (height
maps from terrain tools are 16-bit), RGB(A) images for colour, and raw 16-bit heights (.r16 /
.raw: no header, so size, byte order and height range come from the person). Maps of another
size are resampled bilinearly. Every unreadable file raises MapFileError naming the file and
the reason."""

from __future__ import annotations

import math
import os
import stat
import warnings
from pathlib import Path

import numpy as np
from PIL import Image, UnidentifiedImageError

from core.design_maps import LAYER_INDEX, LAYERS, MAX_SIZE

RAW_SUFFIXES = (".r16", ".raw")
# the image formats a map is read from: no EPS / PostScript (Ghostscript), no exotic decoders
FORMATS = ("PNG", "TIFF", "JPEG", "BMP")
MAX_PIXELS = MAX_SIZE * MAX_SIZE


class MapFileError(Exception):
    """A map file that cannot be read or written; the message names the file."""


def read_image(path: Path | str) -> np.ndarray:
    """(rows, columns, channels) float32 in 0 … 1: 1 channel for greyscale (8 or 16 bit),
    3 for RGB, 4 for RGBA."""
    return _read(Path(path), None)[0]


def read_image_at(path: Path | str, size: tuple[int, int]) -> tuple[np.ndarray, tuple[int, int]]:
    """read_image resampled (bilinearly) to size = (width, height), one channel at a time, so
    a large image never stands in memory as float RGBA; and the image's own size."""
    return _read(Path(path), size)


def _read(path: Path, size: tuple[int, int] | None) -> tuple[np.ndarray, tuple[int, int]]:
    _regular(path)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", Image.DecompressionBombWarning)
            with Image.open(path, formats=FORMATS) as image:
                w, h = image.size
                if w * h > MAX_PIXELS:
                    raise MapFileError(
                        f"{path.name}: {w} × {h} pixels is more than a map holds "
                        f"({MAX_SIZE} × {MAX_SIZE})"
                    )
                image.load()
                if size is None or tuple(size) == (w, h):
                    return _to_array(image, path), (w, h)
                return _resampled(image, path, size), (w, h)
    except MapFileError:
        raise
    except FileNotFoundError:
        raise MapFileError(f"{path}: no such file") from None
    except UnidentifiedImageError:
        raise MapFileError(
            f"{path.name}: not an image Sward reads ({', '.join(FORMATS)})"
        ) from None
    except (Image.DecompressionBombError, Image.DecompressionBombWarning):
        raise MapFileError(f"{path.name}: too many pixels for a map") from None
    except Exception as exc:  # any decoder failure of a damaged file: one line, never a trace
        raise MapFileError(
            f"{path.name}: the image is damaged or truncated ({type(exc).__name__}: {exc})"
        ) from None


def _resampled(image: Image.Image, path: Path, size: tuple[int, int]) -> np.ndarray:
    """The image's channels, each taken alone to float, checked and resized: the memory of
    one full-size float channel at a time."""
    if image.mode in ("P", "LA", "PA", "RGBa", "La"):
        image = image.convert("RGBA")
    elif image.mode == "1":
        image = image.convert("L")
    bands = image.getbands() if image.mode in ("RGB", "RGBA") else (None,)
    channels = []
    for band in bands:
        one = image if band is None else image.getchannel(band)
        values = _to_array(one, path)[..., 0]
        resized = Image.fromarray(values).resize((size[0], size[1]), Image.Resampling.BILINEAR)
        del values
        channels.append(np.asarray(resized, np.float32))
    return np.stack(channels, axis=-1)


def _regular(path: Path) -> None:
    try:
        info = os.stat(path)
    except FileNotFoundError:
        raise MapFileError(f"{path}: no such file") from None
    except OSError as exc:
        raise MapFileError(f"{path}: cannot read ({exc.strerror or exc})") from None
    if not stat.S_ISREG(info.st_mode):
        raise MapFileError(f"{path.name}: not a regular file")


def _to_array(image: Image.Image, path: Path) -> np.ndarray:
    mode = image.mode
    if mode in ("I;16", "I;16B", "I;16L", "I;16N"):
        data = np.asarray(image, np.uint16).astype(np.float32) / 65535.0
    elif mode == "I":  # 32-bit int container of 16-bit PNGs
        data = np.clip(np.asarray(image, np.float64) / 65535.0, 0.0, 1.0).astype(np.float32)
    elif mode == "F":
        data = np.asarray(image, np.float32)
    elif mode in ("L", "1"):
        data = np.asarray(image.convert("L"), np.float32) / 255.0
    elif mode in ("RGB", "RGBA"):
        data = np.asarray(image, np.float32) / 255.0
    elif mode in ("P", "LA", "PA", "RGBa", "La"):
        data = np.asarray(image.convert("RGBA"), np.float32) / 255.0
    else:
        raise MapFileError(
            f"{path.name}: unusable image mode {mode}; use greyscale (8 or 16 bit), RGB or RGBA"
        )
    if data.ndim == 2:
        data = data[..., None]
    if not np.all(np.isfinite(data)):
        raise MapFileError(f"{path.name}: the image holds values that are not numbers")
    if mode == "F" and (data.min() < 0.0 or data.max() > 1.0):
        raise MapFileError(
            f"{path.name}: a floating-point image must hold values in 0 … 1, "
            f"found {float(data.min()):g} … {float(data.max()):g}"
        )
    return data


def read_raw16(
    path: Path | str,
    width: int,
    height: int,
    big_endian: bool = False,
    low: float = 0.0,
    high: float = 1.0,
) -> np.ndarray:
    """A raw 16-bit height field (no header): (rows, columns, 1) in low … high."""
    path = Path(path)
    if not (1 <= width <= MAX_SIZE and 1 <= height <= MAX_SIZE):
        raise MapFileError(f"{path.name}: width and height must be 1 … {MAX_SIZE}")
    if not (math.isfinite(low) and math.isfinite(high)):
        raise MapFileError(
            f"{path.name}: the height range {low:g} … {high:g} must be two finite numbers"
        )
    if not abs(high - low) < float(np.finfo(np.float32).max) / 2:  # heights are float32
        raise MapFileError(f"{path.name}: the height range {low:g} … {high:g} is too wide")
    _regular(path)
    expected = width * height * 2
    size = os.stat(path).st_size  # checked before anything is read
    if size != expected:
        side = math.isqrt(size // 2)
        hint = f"; a square map of {side} × {side}?" if side * side * 2 == size else ""
        raise MapFileError(
            f"{path.name}: {size:,} bytes, but {width} × {height} 16-bit values need "
            f"{expected:,}{hint}"
        )
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise MapFileError(f"{path}: cannot read ({exc.strerror or exc})") from None
    values = np.frombuffer(data, ">u2" if big_endian else "<u2").reshape(height, width)
    return (low + (high - low) * (values.astype(np.float32) / 65535.0))[..., None]


def resample(values: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """(rows, columns, channels) resized bilinearly to size = (width, height)."""
    width, height = size
    if values.shape[1] == width and values.shape[0] == height:
        return values
    channels = [
        np.asarray(
            Image.fromarray(np.ascontiguousarray(values[..., c], np.float32)).resize(
                (width, height), Image.Resampling.BILINEAR
            )
        )
        for c in range(values.shape[2])
    ]
    return np.stack(channels, axis=-1).astype(np.float32)


def fit_channels(values: np.ndarray, layer: str, single: bool) -> np.ndarray:
    """An image's channels as a map wants them: one value (density of one grass type, height),
    RGB + weight (colour: an image without alpha replaces the blades' colour fully), grey or
    RGB light, a flow map's R and G (the trample map)."""
    channels = LAYERS[LAYER_INDEX[layer]].channels
    rgb = values[..., :3] if values.shape[2] >= 3 else np.repeat(values[..., :1], 3, axis=2)
    grey = (
        values[..., :1]
        if values.shape[2] < 3
        else (0.299 * rgb[..., :1] + 0.587 * rgb[..., 1:2] + 0.114 * rgb[..., 2:3])
    )
    if single or channels == 1:
        return grey.astype(np.float32)
    if layer == "color":
        alpha = values[..., 3:4] if values.shape[2] == 4 else np.ones_like(grey)
        return np.concatenate([rgb, alpha], axis=2).astype(np.float32)
    if channels == 3:
        return rgb.astype(np.float32)
    if channels == 2 and values.shape[2] >= 3:  # the trample map from a flow map: R and G
        return rgb[..., :2].astype(np.float32)
    return np.repeat(grey, channels, axis=2).astype(np.float32)


def quantized(values: np.ndarray) -> np.ndarray:
    """0 … 1 as the 16-bit integers the PNG and raw files hold (NaN as 0)."""
    return np.round(np.clip(np.nan_to_num(values, nan=0.0), 0.0, 1.0) * 65535.0).astype(np.uint16)


def write_map(path: Path | str, values: np.ndarray, big_endian: bool = False) -> None:
    """Save (rows, columns, channels) in 0 … 1: .r16 / .raw raw 16-bit of the first channel,
    otherwise PNG — 16-bit greyscale for one channel, 8-bit RGB or RGBA for three or four."""
    path = Path(path)
    v = np.clip(np.nan_to_num(values, nan=0.0), 0.0, 1.0)
    try:
        if path.suffix.lower() in RAW_SUFFIXES:
            raw = quantized(v[..., 0]).astype(">u2" if big_endian else "<u2")
            path.write_bytes(raw.tobytes())
        elif v.shape[2] == 1:
            grey = quantized(v[..., 0])
            Image.fromarray(grey).save(path, format="PNG")  # uint16: mode I;16
        else:
            rgb = v if v.shape[2] in (3, 4) else np.repeat(v[..., :1], 3, axis=2)
            Image.fromarray(np.round(rgb * 255.0).astype(np.uint8)).save(path, format="PNG")
    except OSError as exc:
        raise MapFileError(f"{path}: cannot write ({exc.strerror or exc})") from None
