"""The process the designer's render processes are forked from (render/process_start.py).

A render process spends about a second of CPU importing numpy, numba and Sward's render modules
and loading numba's compiled kernels before it makes its GL context, and the designer starts two,
and another whenever one dies. This process does that once and forks a render process for each
request: the child takes the request's environment, makes its own GL context (none is made here
before a fork) and serves its window over the socket end the request carried
(render/render_server.py serve), and ends as `python -m render.render_server` would. This process
is the children's parent: it tells the window a child's exit status once the child has ended,
and until then the child's pid stays its own.

One request or reply is one datagram of a SOCK_SEQPACKET socket pair, a JSON object:
    {"role": ROLE, "env": {...}} and the socket end      ->  {"pid": PID}
    {"status": PID}  (once that child has ended)         ->  {"code": CODE or null}
It ends when the window's end of the pair closes.
"""

from __future__ import annotations

import contextlib
import json
import os
import socket
import sys
import traceback
from typing import NoReturn

MAX_REQUEST = 1 << 20  # bytes: an environment is far smaller


def _warm() -> None:
    """A render process's imports, and numba's first load of a compiled kernel (its
    registries), which every process pays once."""
    import numpy as np

    import core.noise
    import render.render_server

    del render
    core.noise.perlin2d(np.zeros((2, 2)), np.zeros((2, 2)), 1, 0)


def _name(name: str) -> None:
    """The name `top` and `ps -o comm` show for this process (its command line stays the fork
    server's): a render process by its role rather than as the server it came from."""
    try:
        with open("/proc/self/comm", "w") as comm:
            comm.write(name[:15])
    except OSError:
        pass  # not Linux, or not allowed: the name stays


def _serve_child(request: dict, fd: int, server: socket.socket) -> None:
    """In the child: the render process of the request's role, to its end."""
    from multiprocessing.connection import Connection

    from render.render_server import serve

    server.close()
    _name(f"sward-{request['role']}")
    os.environ.clear()
    os.environ.update(request["env"])
    serve(Connection(fd), request["role"])


def _child(request: dict, fd: int, server: socket.socket) -> NoReturn:
    """The forked child's life: its render process, then its exit with the status `python -m
    render.render_server` would end with (1 and the traceback on stderr for an error). It
    leaves through os._exit, as multiprocessing's forked children do: the interpreter's own
    exit would run the fork server's exit handlers and tear down the GL driver and every
    module object one by one, work for a process that is ending anyway (most of what a closing
    window waits for)."""
    code = 0
    try:
        _serve_child(request, fd, server)
    except SystemExit as stop:
        code = stop.code if isinstance(stop.code, int) else int(stop.code is not None)
    except BaseException:
        traceback.print_exc()
        code = 1
    finally:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os._exit(code)


def main(fd: int) -> None:
    server = socket.socket(fileno=fd)
    _name("sward-forks")
    try:
        _warm()
        while True:
            data, fds, _flags, _address = socket.recv_fds(server, MAX_REQUEST, 1)
            if not data:
                return  # the window went away
            request = json.loads(data)
            if "status" in request:
                try:
                    _, status = os.waitpid(int(request["status"]), 0)
                    code = os.waitstatus_to_exitcode(status)
                except ChildProcessError:
                    code = None  # not a child of this process, or asked for before
                server.send(json.dumps({"code": code}).encode())
                continue
            pid = os.fork()
            if pid == 0:
                _child(request, fds[0], server)
            for received in fds:
                os.close(received)
            server.send(json.dumps({"pid": pid}).encode())
    except (ConnectionResetError, BrokenPipeError, KeyboardInterrupt):
        return


if __name__ == "__main__":  # python -m render.fork_server FD (render/process_start.py)
    main(int(sys.argv[1]))
