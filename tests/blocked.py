"""A pytest plugin that makes Qt and GL unimportable (`pytest -p tests.blocked`): the proof that
core/ and the designer's controllers need neither (STYLE.md; `make test` runs tests/core and
tests/app this way)."""

from __future__ import annotations

import importlib.abc
import sys

BLOCKED = ("PySide6", "shiboken6", "pyqtgraph", "moderngl", "glcontext", "render", "widgets")


class _Blocker(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in BLOCKED:
            raise ImportError(f"{name} is blocked in this run (tests/blocked.py)")
        return None


def pytest_configure(config) -> None:
    loaded = sorted(m for m in sys.modules if m.split(".")[0] in BLOCKED)
    if loaded:
        raise RuntimeError(f"already imported before blocking: {', '.join(loaded[:5])}")
    sys.meta_path.insert(0, _Blocker())


def pytest_addoption(parser) -> None:
    # pytest-qt is switched off in this run (`-p no:pytest-qt`): its settings stay valid
    for name in ("qt_api", "qt_log_level_fail"):
        parser.addini(name, "pytest-qt's setting, unused while Qt is blocked")
