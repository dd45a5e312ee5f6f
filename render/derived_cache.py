"""What the renderer derives from a patch or the terrain at a cost, kept on disk by the content
it is of: the light tables' sums over a patch's blades (render/facing.py) and how far the
ground mesh's vertices sink under the height map (render/design_maps.py). Handed between the
designer's two render processes, and from one run of Sward to the next.

Both render processes need the sums of every new patch, and on a CPU renderer their build (the
slope sums, the facing tables, the ground's sink) takes a good part of a second
(docs/edits.md). The first process to need something claims it (a claim file, made exclusively),
builds it and writes it; the other waits for that file instead of building it too (or, when it
must not wait, draws with what it holds). The folder outlives the designer: the next start, a
`sward render` of the same scene, an undo to a patch built in an earlier session find it there.

The folder is SWARD_CACHE (a path, or "off"), else $XDG_CACHE_HOME/sward/derived or
~/.cache/sward/derived; the designer hands its render processes one folder (SHARED_DIR_ENV), a
temporary one when the cache is off. A file's name carries a fingerprint of core/'s sources, so
what other code made is never read, and the content digest of what it was made from. Files
are read without pickles and checked (shapes, finiteness) before use: one that fails is built
again. The folder keeps its newest files up to MAX_BYTES.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import re
import threading
import time
import zipfile
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, TypeVar

import numpy as np

import core

if TYPE_CHECKING:  # the window's process names the folder and imports no numba
    from core.light_moments import LightMoments
    from core.slopes import SlopeMoments

CACHE_ENV = "SWARD_CACHE"
SHARED_DIR_ENV = "SWARD_SHARED_SUMS"
MAX_BYTES = 256 * 2**20  # the folder's newest files up to this size are kept
CLAIM_STALE_S = 120.0  # a claim this old (or of a process that is gone) is given up
WAIT_S = 30.0  # the longest a process waits for another's build before building it itself
POLL_S = 0.02
_NAME = re.compile(r"^(slope|facing|sink)-[0-9a-f]{16}-[0-9a-f]{32}\.npz$")

T = TypeVar("T")


def folder() -> Path | None:
    """Where sums are kept, made if missing; None when the cache is off or cannot be made."""
    shared = os.environ.get(SHARED_DIR_ENV)
    if shared:
        return Path(shared)
    setting = os.environ.get(CACHE_ENV, "")
    if setting.lower() == "off":
        return None
    if setting:
        base = Path(setting)
    else:
        home = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
        base = Path(home) / "sward" / "derived"
    try:
        base.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return base if os.access(base, os.W_OK) else None


@lru_cache(maxsize=1)
def code_fingerprint() -> str:
    """A digest of core/'s sources and numpy's version: sums made by other code are not ours."""
    digest = hashlib.blake2b(np.__version__.encode(), digest_size=8)
    for source in sorted(Path(core.__file__).parent.glob("*.py")):
        digest.update(source.name.encode())
        digest.update(source.read_bytes())
    return digest.hexdigest()


def path_for(kind: str, key: str) -> Path | None:
    base = folder()
    return None if base is None else base / f"{kind}-{code_fingerprint()}-{key}.npz"


# -- the two kinds of sums as arrays -----------------------------------------------------------
_FIELDS = ("powers", "signed", "total")


def _moments_arrays(prefix: str, m: LightMoments) -> dict[str, np.ndarray]:
    return {f"{prefix}{name}": getattr(m, name).astype(np.float32) for name in _FIELDS}


def _moments_of(f, prefix: str) -> LightMoments:
    from core.light_moments import LightMoments

    # kept in single precision as written: no double copy of the slope sums (their largest
    # array) in a start's first frame; LightMoments.lit works in either
    powers, signed, total = (np.asarray(f[f"{prefix}{name}"], np.float32) for name in _FIELDS)
    shape = total.shape
    if powers.shape[:-1] != shape or signed.shape != (*shape, 3):
        raise ValueError("sums of mismatched shapes")
    if not all(np.isfinite(a).all() for a in (powers, signed, total)):
        raise ValueError("sums that are not finite")
    return LightMoments(powers, signed, total)


def _slope_arrays(m: SlopeMoments) -> dict[str, np.ndarray]:
    return {
        **_moments_arrays("upright_", m.upright),
        **_moments_arrays("sheared_", m.sheared),
        "size": np.array([m.elevations, m.azimuths]),
    }


def _slope_of(f) -> SlopeMoments:
    from core.slopes import SlopeMoments

    elevations, azimuths = (int(v) for v in f["size"])
    upright, sheared = _moments_of(f, "upright_"), _moments_of(f, "sheared_")
    if upright.total.shape[-1] != elevations * azimuths:
        raise ValueError("sums of another table size")
    return SlopeMoments(upright, sheared, elevations, azimuths)


def _facing_arrays(m: LightMoments) -> dict[str, np.ndarray]:
    return _moments_arrays("", m)


def _facing_of(f) -> LightMoments:
    return _moments_of(f, "")


def _sink_arrays(made: tuple[np.ndarray, np.ndarray]) -> dict[str, np.ndarray]:
    return {"sink": made[0], "excess": made[1]}


def _sink_of(f) -> tuple[np.ndarray, np.ndarray]:
    sink, excess = (np.asarray(f[name], np.float32) for name in ("sink", "excess"))
    if sink.ndim != 2 or sink.shape != (excess.shape[0] + 1, excess.shape[1] + 1):
        raise ValueError("a sink of mismatched shapes")
    if not (np.isfinite(sink).all() and np.isfinite(excess).all()):
        raise ValueError("a sink that is not finite")
    return sink, excess


_KINDS: dict[str, tuple[Callable, Callable]] = {
    "slope": (_slope_arrays, _slope_of),
    "facing": (_facing_arrays, _facing_of),
    "sink": (_sink_arrays, _sink_of),
}


# -- reading, writing, claiming ----------------------------------------------------------------
_ahead: dict[tuple[str, str], Future] = {}  # reads begun by read_ahead, by kind and key
_ahead_lock = threading.Lock()
_reader: ThreadPoolExecutor | None = None
AHEAD = 8  # the most reads begun and not yet taken (the oldest are forgotten)


def beside(work: Callable[..., T], *args) -> Future[T]:
    """Run `work(*args)` on the one thread that reads ahead: what a first frame will need and
    can be made without GL (files read, numpy arrays), while the caller sets up the rest. Its
    waits (file reads, numpy's loops) are mostly outside the interpreter's lock."""
    global _reader
    with _ahead_lock:
        if _reader is None:
            _reader = ThreadPoolExecutor(1, thread_name_prefix="sward-ahead")
        return _reader.submit(work, *args)


def read_ahead(kind: str, key: str) -> None:
    """Begin reading what is kept under `key` beside the caller, for the `load` that will ask
    for it (a renderer's first frame, after its conversion)."""
    if path_for(kind, key) is None:
        return
    with _ahead_lock:
        if (kind, key) in _ahead:
            return
    future = beside(_load, kind, key)
    with _ahead_lock:
        _ahead[(kind, key)] = future
        while len(_ahead) > AHEAD:
            del _ahead[next(iter(_ahead))]


def load(kind: str, key: str):
    """The sums kept under `key`, or None (none, or a file that is not whole or not sums)."""
    with _ahead_lock:
        ahead = _ahead.pop((kind, key), None)
    if ahead is not None:
        found = ahead.result()
        if found is not None:
            return found
    return _load(kind, key)


def _load(kind: str, key: str):
    path = path_for(kind, key)
    if path is None or not path.is_file():
        return None
    try:
        with open(path, "rb") as file:
            f = np.load(file, allow_pickle=False)
            if not isinstance(f, np.lib.npyio.NpzFile):
                raise ValueError("not an archive of arrays")
            with f:
                return _KINDS[kind][1](f)
    except (OSError, KeyError, ValueError, EOFError, zipfile.BadZipFile):  # not whole, not ours
        return None


def save(kind: str, key: str, sums) -> None:
    """Write the sums under `key` (single precision: their tables differ by under 1e-6), whole
    or not at all, then keep the folder within MAX_BYTES."""
    path = path_for(kind, key)
    if path is None:
        return
    partial = path.with_name(f".{path.name}.{os.getpid()}")
    try:
        with open(partial, "wb") as file:
            np.savez(file, **_KINDS[kind][0](sums))
        os.replace(partial, path)  # the reader sees the whole file or none
        _prune(path.parent)
    except OSError:  # the folder went away or is full: nothing kept
        partial.unlink(missing_ok=True)


def _prune(base: Path) -> None:
    keep_newest([p for p in base.iterdir() if _NAME.match(p.name)], MAX_BYTES)


def keep_newest(files: list[Path], max_bytes: int) -> None:
    """Remove the oldest of `files` beyond the newest `max_bytes`."""
    found = []
    for p in files:
        with contextlib.suppress(OSError):
            st = p.stat()
            found.append((st.st_mtime, st.st_size, p))
    total = 0
    for _mtime, size, p in sorted(found, key=lambda f: f[0], reverse=True):
        total += size
        if total > max_bytes:
            p.unlink(missing_ok=True)


def _claim_path(path: Path) -> Path:
    return path.with_name(f".{path.name}.claim")


def _claim(path: Path) -> bool:
    """Make the claim file for `path`; False if another live process holds it."""
    claim = _claim_path(path)
    for _ in range(2):
        try:
            fd = os.open(claim, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            if not _stale(claim):
                return False
            claim.unlink(missing_ok=True)  # its maker is gone: take it over
            continue
        except OSError:
            return True  # no claims in this folder: build, as without one
        with os.fdopen(fd, "w") as file:
            file.write(str(os.getpid()))
        return True
    return False


def _stale(claim: Path) -> bool:
    try:
        pid = int(claim.read_text() or "0")
        age = time.time() - claim.stat().st_mtime
    except (OSError, ValueError):
        return True
    if age > CLAIM_STALE_S or pid <= 0:
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except PermissionError:
        return False
    return False


def fetch(kind: str, key: str, build: Callable[[], T], wait: bool = True) -> T | None:
    """The sums under `key`: read from the folder, or built here and written there. While
    another process builds them (its claim), wait for its file (`wait`) or return None."""
    path = path_for(kind, key)
    if path is None:
        return build()
    found = load(kind, key)
    if found is not None:
        return found
    deadline = time.monotonic() + WAIT_S
    while not _claim(path):
        if not wait:
            return None
        if time.monotonic() > deadline:
            return build()  # the other is stuck: do not wait for ever
        time.sleep(POLL_S)
        found = load(kind, key)
        if found is not None:
            return found
    try:
        found = load(kind, key)  # written between our look and our claim
        if found is None:
            found = build()
            save(kind, key, found)
        return found
    finally:
        _claim_path(path).unlink(missing_ok=True)
