"""The designer's render processes start before its window's modules load (render/
process_start.py): the window takes the processes started for its folder, and starts its own
when they went away or were started for another."""

from __future__ import annotations

import socket
import subprocess
import sys
from pathlib import Path

import pytest

from render import process_start


@pytest.fixture
def fake_spawn(monkeypatch):
    """Processes that only wait, in place of render processes; all ended after the test."""
    made = []

    def spawn(role, shared_dir, shared_env):
        process = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
        mine, theirs = socket.socketpair()
        theirs.close()
        made.append(process)
        return process, mine

    early: dict = {}
    monkeypatch.setattr(process_start, "spawn", spawn)
    monkeypatch.setattr(process_start, "_early", early)
    yield made
    for _process, sock, _folder in early.values():
        sock.close()
    for process in made:
        process.kill()
        process.wait()


def test_the_window_takes_the_processes_started_early_for_its_folder(fake_spawn):
    process_start.start_early(process_start.ROLES, "/kept", "SWARD_SHARED_SUMS")
    process_start.start_early(process_start.ROLES, "/kept", "SWARD_SHARED_SUMS")  # no more
    assert len(fake_spawn) == 2
    draft = process_start.take(process_start.DRAFT, "/kept")
    assert draft is not None and draft[0] is fake_spawn[0]
    assert process_start.take(process_start.DRAFT, "/kept") is None  # taken once
    draft[1].close()


def test_processes_of_another_folder_or_gone_are_not_taken(fake_spawn):
    process_start.start_early(process_start.ROLES, "/kept", "SWARD_SHARED_SUMS")
    assert process_start.take(process_start.DRAFT, "/elsewhere") is None
    assert fake_spawn[0].poll() is not None  # ended, not left running unowned
    fake_spawn[1].kill()
    fake_spawn[1].wait()
    assert process_start.take(process_start.FULL, "/kept") is None


def _parent(pid: int) -> int:
    stat = Path(f"/proc/{pid}/stat").read_text()
    return int(stat.rsplit(")", 1)[1].split()[1])


def _started(role: str, folder) -> tuple:
    from multiprocessing.connection import Connection

    from render import protocol as msg

    process, mine = process_start.spawn(role, str(folder), "SWARD_SHARED_SUMS")
    conn = Connection(mine.detach())
    assert conn.poll(120), "the render process did not answer"
    hello = conn.recv()
    assert isinstance(hello, msg.Hello) and hello.pid == process.pid
    return process, conn


def test_render_processes_are_forked_from_one_that_did_the_imports(tmp_path):
    """Both of a window's render processes, and one started again after a process died, come
    from the fork server: one process's imports, each its own GL context; the window learns
    how each ended, as from a process of its own."""
    from render import protocol as msg

    first, first_conn = _started(process_start.DRAFT, tmp_path)
    server = process_start._server
    assert server is not None and _parent(first.pid) == server.process.pid
    second, second_conn = _started(process_start.FULL, tmp_path)
    assert process_start._server is server and _parent(second.pid) == server.process.pid
    assert second.pid != first.pid and first.poll() is None
    # `top` names each by its role, not as the fork server
    assert Path(f"/proc/{first.pid}/comm").read_text().strip() == "sward-draft"
    assert Path(f"/proc/{second.pid}/comm").read_text().strip() == "sward-full"
    first.kill()
    assert first.wait(timeout=30) == -9  # what the window shows: "killed by signal 9"
    second_conn.send(msg.Quit())
    assert second.wait(timeout=30) == 0
    first_conn.close()
    second_conn.close()
    # the fork server gone, the next render process starts all the same (a new server)
    server.process.kill()
    server.process.wait()
    third, third_conn = _started(process_start.DRAFT, tmp_path)
    assert process_start._server is not server
    third_conn.send(msg.Quit())
    assert third.wait(timeout=30) == 0
    third_conn.close()


def test_a_fork_server_gone_before_it_answered_leaves_no_hang(tmp_path):
    """The fork server dies before it forked what was asked (its imports broken, killed): the
    window's process counts that render process as ended, and the next one starts."""
    if process_start._server is not None:  # a new server, still at its imports below
        process_start._server.process.kill()
        process_start._server.process.wait()
    process, mine = process_start.spawn(process_start.DRAFT, str(tmp_path), "SWARD_SHARED_SUMS")
    server = process_start._server
    assert server is not None and process.poll() is None  # being forked: its imports first
    server.process.kill()
    server.process.wait()
    assert process.wait(timeout=30) == 1 and process.poll() == 1
    process.kill()  # nothing to kill: no error
    assert mine.recv(1) == b""  # nobody holds the other end
    mine.close()
    again, again_conn = _started(process_start.DRAFT, tmp_path)
    again.kill()
    assert again.wait(timeout=30) == -9
    again_conn.close()


def test_a_forked_render_process_that_fails_says_why_and_ends_with_status_1(tmp_path):
    """An error inside a forked render process (here a message that is none): the window gets
    its traceback and the process ends with status 1, as a process of its own would; one that
    quits ends with 0 (above)."""
    from render import protocol as msg

    process, conn = _started(process_start.FULL, tmp_path)
    conn.send_bytes(b"not a message")
    assert conn.poll(30)
    failed = conn.recv()
    assert isinstance(failed, msg.Failed) and "Traceback" in failed.traceback
    assert process.wait(timeout=30) == 1
    conn.close()
