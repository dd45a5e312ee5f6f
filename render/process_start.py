"""Starting the designer's render processes (render/render_server.py). A process takes most of a
second to import its modules and make its GL context: `start_early` at the top of `sward` starts
both while the window's process imports Qt and builds its widgets, and render/render_client.py
takes them (`take`) instead of starting its own. Nothing here imports Qt, GL or numpy: it runs
before them."""

from __future__ import annotations

import os
import socket
import subprocess
import sys

DRAFT, FULL = "draft", "full"
ROLES = (DRAFT, FULL)  # the designer's: a draft for every change, then the full frame

_early: dict[str, tuple[subprocess.Popen, socket.socket, str]] = {}


def spawn(role: str, shared_dir: str, shared_env: str) -> tuple[subprocess.Popen, socket.socket]:
    """A new render process of `role`, talking over a socket pair (a module run with -m:
    nothing of the window's program is imported again there), and the window's end."""
    mine, theirs = socket.socketpair()
    process = subprocess.Popen(
        [sys.executable, "-m", "render.render_server", role, str(theirs.fileno())],
        pass_fds=(theirs.fileno(),),
        env={**os.environ, shared_env: shared_dir},
    )
    theirs.close()
    return process, mine


def start_early(roles: tuple[str, ...], shared_dir: str, shared_env: str) -> None:
    """Start a render process of each role now, for the window made later."""
    for role in roles:
        if role not in _early:
            _early[role] = (*spawn(role, shared_dir, shared_env), shared_dir)


def take(role: str, shared_dir: str) -> tuple[subprocess.Popen, socket.socket] | None:
    """The process of `role` started early with this folder and still running, or None."""
    early = _early.pop(role, None)
    if early is None:
        return None
    process, sock, folder = early
    if folder != shared_dir or process.poll() is not None:
        sock.close()
        process.kill()  # it holds nothing yet; waited for, so that no zombie is left
        process.wait()
        return None
    return process, sock
