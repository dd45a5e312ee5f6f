"""Arrays the window and its render processes share: a numpy array over a file both map (in
/dev/shm: memory, not disk). No GL here: the window's process imports it."""

from __future__ import annotations

import contextlib
import mmap

import numpy as np


class MappedArray:
    """A numpy array over a file both processes map (in /dev/shm: memory, not disk)."""

    def __init__(self, path: str, shape: tuple[int, ...], dtype=np.float32) -> None:
        self.path = path
        nbytes = int(np.prod(shape)) * np.dtype(dtype).itemsize
        with open(path, "r+b") as file:  # the mapping keeps its own descriptor
            self._map = mmap.mmap(file.fileno(), nbytes)
        self.array = np.ndarray(shape, dtype, buffer=self._map)

    def close(self) -> None:
        del self.array
        with contextlib.suppress(BufferError):  # a view still held: unmapped when it goes
            self._map.close()
