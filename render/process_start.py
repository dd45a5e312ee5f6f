"""Starting the designer's render processes (render/render_server.py). A process takes most of a
second to import its modules and make its GL context: `start_early` at the top of `sward` starts
both while the window's process imports Qt and builds its widgets, and render/render_client.py
takes them (`take`) instead of starting its own. They are forked from one process that has done
their imports (render/fork_server.py), started with the first of them and kept for the next: a
window's second process, and one started again after its predecessor died, skip the imports.
Where that process cannot run (no fork) or has gone, a render process is started on its own.
Nothing here imports Qt, GL or numpy: it runs before them."""

from __future__ import annotations

import atexit
import contextlib
import json
import os
import select
import signal
import socket
import subprocess
import sys
from collections import deque

DRAFT, FULL = "draft", "full"
ROLES = (DRAFT, FULL)  # the designer's: a draft for every change, then the full frame
REPLY_WAIT_S = 60.0  # the longest the fork server may take to answer (its imports first)

_early: dict[str, tuple[subprocess.Popen | Forked, socket.socket, str]] = {}


class _ForkServer:
    """render/fork_server.py running, and the window's end of its socket pair."""

    def __init__(self) -> None:
        mine, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        self.process = subprocess.Popen(
            [sys.executable, "-m", "render.fork_server", str(theirs.fileno())],
            pass_fds=(theirs.fileno(),),
        )
        theirs.close()
        mine.settimeout(REPLY_WAIT_S)
        self.sock = mine
        self.pending: deque[Forked] = deque()  # forks asked for whose pid has not come back

    def alive(self) -> bool:
        return self.process.poll() is None and self.sock.fileno() >= 0

    def stop(self) -> None:
        """Its end of the pair closed, it ends; the processes it forked go on with theirs."""
        self.sock.close()
        try:
            self.process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()

    def _reply(self) -> dict:
        data = self.sock.recv(4096)
        if not data:
            raise ConnectionResetError("the fork server ended")
        return json.loads(data)

    def fork(self, role: str, env: dict[str, str], theirs: socket.socket) -> Forked:
        request = json.dumps({"role": role, "env": env}).encode()
        socket.send_fds(self.sock, [request], [theirs.fileno()])
        forked = Forked(self)
        self.pending.append(forked)
        return forked

    def settle(self) -> None:
        """Read the pids of the forks asked for (they answer in order). If the server ended
        or stopped answering first, those never started: they count as ended (exit 1)."""
        try:
            while self.pending:
                self.pending[0].known_pid = int(self._reply()["pid"])
                self.pending.popleft()
        except (OSError, ValueError, KeyError):
            while self.pending:
                self.pending.popleft().never_started()

    def status(self, pid: int) -> int | None:
        """The exit status of the child `pid`, which has ended (None if it cannot be known)."""
        try:
            self.settle()
            self.sock.send(json.dumps({"status": pid}).encode())
            return self._reply()["code"]
        except (OSError, ValueError, KeyError):
            return None


class Forked:
    """A render process forked by the fork server: what render_client uses of a Popen."""

    def __init__(self, server: _ForkServer) -> None:
        self.server = server
        self.known_pid: int | None = None
        self.returncode: int | None = None
        self._pidfd: int | None = None

    @property
    def pid(self) -> int:
        if self.known_pid is None:
            self.server.settle()
        assert self.known_pid is not None
        return self.known_pid

    def never_started(self) -> None:
        self.known_pid, self.returncode = 0, 1

    def _ended(self, timeout: float | None) -> bool:
        """Whether it has ended, waiting up to `timeout`; its exit status read if so."""
        pid = self.pid
        if self.returncode is not None:
            return True  # never started, or read before
        if self._pidfd is None:
            try:
                self._pidfd = os.pidfd_open(pid)
            except ProcessLookupError:
                self._finish()  # reaped already (its server ended)
                return True
        if not select.select([self._pidfd], [], [], timeout)[0]:
            return False
        self._finish()
        return True

    def poll(self) -> int | None:
        if self.known_pid is None:
            return None  # being forked still (the server's imports first)
        self._ended(0.0)
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        if not self._ended(timeout):
            raise subprocess.TimeoutExpired(f"render process {self.pid}", timeout or 0.0)
        assert self.returncode is not None
        return self.returncode

    def kill(self) -> None:
        if self.returncode is None and self.pid > 0:
            with contextlib.suppress(ProcessLookupError):
                os.kill(self.pid, signal.SIGKILL)

    def _finish(self) -> None:
        code = self.server.status(self.pid)
        # the status unknown (its server gone): a process that ended all the same
        self.returncode = code if code is not None else -signal.SIGKILL
        if self._pidfd is not None:
            os.close(self._pidfd)
            self._pidfd = None


_server: _ForkServer | None = None


def _fork_server() -> _ForkServer | None:
    """The running fork server, started if there is none; None where fork is not had."""
    global _server
    if not (hasattr(os, "fork") and hasattr(os, "pidfd_open") and hasattr(socket, "send_fds")):
        return None
    if _server is None or not _server.alive():
        if _server is None:
            atexit.register(_stop_server)
        else:
            _server.stop()  # it ended: its socket closed, its status read
        _server = _ForkServer()
    return _server


def _stop_server() -> None:
    if _server is not None:
        _server.stop()


def spawn(
    role: str, shared_dir: str, shared_env: str
) -> tuple[subprocess.Popen | Forked, socket.socket]:
    """A new render process of `role`, talking over a socket pair, and the window's end: forked
    by the fork server, or where it cannot, a module run with -m (nothing of the window's
    program is imported again there)."""
    mine, theirs = socket.socketpair()
    env = {**os.environ, shared_env: shared_dir}
    process: subprocess.Popen | Forked | None = None
    server = _fork_server()
    if server is not None:
        with contextlib.suppress(OSError):
            process = server.fork(role, env, theirs)
    if process is None:
        process = subprocess.Popen(
            [sys.executable, "-m", "render.render_server", role, str(theirs.fileno())],
            pass_fds=(theirs.fileno(),),
            env=env,
        )
    theirs.close()
    return process, mine


def start_early(roles: tuple[str, ...], shared_dir: str, shared_env: str) -> None:
    """Start a render process of each role now, for the window made later."""
    for role in roles:
        if role not in _early:
            _early[role] = (*spawn(role, shared_dir, shared_env), shared_dir)


def take(role: str, shared_dir: str) -> tuple[subprocess.Popen | Forked, socket.socket] | None:
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
