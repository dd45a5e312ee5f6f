"""Helpers for tests that take a valid project file apart and write changed copies of it."""

from __future__ import annotations

import json
import zipfile
from collections.abc import Callable
from pathlib import Path


def project_parts(path: Path) -> tuple[dict, bytes]:
    """project.json as data and maps.npz as bytes."""
    with zipfile.ZipFile(path) as z:
        return json.loads(z.read("project.json")), z.read("maps.npz")


def write_project(path: Path, data: dict, maps: bytes, **zip_kwargs) -> Path:
    with zipfile.ZipFile(path, "w", **zip_kwargs) as z:
        z.writestr("project.json", json.dumps(data))
        z.writestr("maps.npz", maps)
    return path


def variant(path: Path, data: dict, maps: bytes, change: Callable[[dict], object]) -> Path:
    """A copy of the project with `change` applied to a copy of its data."""
    copy = json.loads(json.dumps(data))
    change(copy)
    return write_project(path, copy, maps)


def leaves(value, path=()):
    """Paths to every value of the data (lists of numbers count as one value)."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield from leaves(v, (*path, k))
    elif isinstance(value, list) and value and not all(isinstance(v, int | float) for v in value):
        for i, v in enumerate(value):
            yield from leaves(v, (*path, i))
    else:
        yield path


def replaced(data: dict, where: tuple, value) -> dict:
    copy = json.loads(json.dumps(data))
    node = copy
    for key in where[:-1]:
        node = node[key]
    node[where[-1]] = value
    return copy
