"""`sward ARGS` run as a process of its own, forked from one that has done its imports.

A `sward` process spends about two seconds of CPU before its first frame on what every run
repeats: importing numpy, numba, scipy, moderngl and Sward, and loading numba's compiled
kernels. The tests run `sward` some hundred times, so each test process keeps one warm process
(this module run as a script) that has done that once and forks a child for every run. The
child is a process as `python -m app.cli ARGS` makes one: its own environment, folder,
standard streams (files, as a pipe is to a program), exit status, GL context (none is made
before the fork) and interpreter exit (atexit, threads); `app.cli` is its `__main__`, so the
worker processes it spawns start as they do for a user. What a fresh interpreter does that a
fork does not (the imports themselves, `python -m` finding the module) keeps a test of its own
run with `sys.executable` (tests/test_cli.py).
"""

from __future__ import annotations

import atexit
import contextlib
import json
import os
import signal
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


class _Server:
    """The warm process of this test process, started at its first run."""

    def __init__(self) -> None:
        self.process = subprocess.Popen(
            [sys.executable, "-m", "tests.cli_process"],
            cwd=ROOT,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            bufsize=1,
        )
        self.lock = threading.Lock()
        atexit.register(self.close)

    def close(self) -> None:
        """Its input closed, it ends after the run it is in (none, between tests)."""
        self.process.stdin.close()
        self.process.wait(timeout=60)
        self.process.stdout.close()

    def run(self, args, env, timeout) -> subprocess.CompletedProcess:
        with self.lock, tempfile.TemporaryDirectory(prefix="sward-run-") as folder:
            out, err = Path(folder, "stdout"), Path(folder, "stderr")
            request = {"args": list(args), "env": dict(env), "cwd": os.getcwd()}
            request.update(stdout=str(out), stderr=str(err))
            self.process.stdin.write(json.dumps(request) + "\n")
            pid = int(self.process.stdout.readline())
            killed = threading.Event()

            def kill() -> None:
                killed.set()
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(pid, signal.SIGKILL)

            timer = threading.Timer(timeout, kill)
            timer.start()
            try:
                status = int(self.process.stdout.readline())
            finally:
                timer.cancel()
            if killed.is_set():
                raise subprocess.TimeoutExpired(["sward", *args], timeout)
            return subprocess.CompletedProcess(
                ["sward", *args],
                status,
                out.read_text(errors="replace"),
                err.read_text(errors="replace"),
            )


_server: _Server | None = None


def run(args, env, timeout: float) -> subprocess.CompletedProcess:
    """`sward ARGS` with `env` as its environment, as subprocess.run(capture_output=True,
    text=True) returns it."""
    global _server
    if _server is None or _server.process.poll() is not None:
        _server = _Server()
    return _server.run(args, env, timeout)


# -- the warm process ----------------------------------------------------------------------------


def _warm() -> None:
    """What every `sward` run does before its own work: the command line's modules and what
    they import, and numba's kernels loaded once (its first dispatch in a process loads its
    registries and checks BLAS through scipy)."""
    import numpy as np

    import app.bench
    import app.cli
    import app.cli_input
    import app.export
    import app.profile
    import app.quality
    import app.sweep
    import app.tune
    import core.noise
    import render.headless

    del app, render
    core.noise.perlin2d(np.zeros((2, 2)), np.zeros((2, 2)), 1, 0)


def _child(request: dict) -> None:
    """In the forked child: become `python -m app.cli ARGS` and exit as it does."""
    os.setpgid(0, 0)  # its own group: a timeout stops the workers it started too
    os.chdir(request["cwd"])
    os.environ.clear()
    os.environ.update(request["env"])
    streams = [
        os.open(os.devnull, os.O_RDONLY),
        os.open(request["stdout"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600),
        os.open(request["stderr"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600),
    ]
    for fd, stream in enumerate(streams):
        os.dup2(stream, fd)
        os.close(stream)
    sys.stdin = open(0, closefd=False)
    sys.stdout = open(1, "w", closefd=False)
    sys.stderr = open(2, "w", closefd=False, errors="backslashreplace")
    import app.cli

    sys.modules["__main__"] = app.cli
    sys.argv = [app.cli.__file__, *request["args"]]
    sys.exit(app.cli.main(request["args"]))


def _serve() -> None:
    requests = os.fdopen(os.dup(0), "r")
    replies = os.fdopen(os.dup(1), "w", buffering=1)
    null = os.open(os.devnull, os.O_RDWR)
    os.dup2(null, 0)
    os.dup2(null, 1)
    _warm()
    for line in requests:
        request = json.loads(line)
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            requests.close()
            replies.close()
            _child(request)
        replies.write(f"{pid}\n")
        _, status = os.waitpid(pid, 0)
        replies.write(f"{os.waitstatus_to_exitcode(status)}\n")


if __name__ == "__main__":
    _serve()
