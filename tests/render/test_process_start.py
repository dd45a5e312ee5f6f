"""The designer's render processes start before its window's modules load (render/
process_start.py): the window takes the processes started for its folder, and starts its own
when they went away or were started for another."""

from __future__ import annotations

import socket
import subprocess
import sys

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
