"""The Qt binding Sward runs on: PySide6 6.12.0 lost a reference to True with every signal
delivered to a Python slot, so a long session (or the test run) aborted. pyproject excludes it;
this test fails on any binding with that fault."""

import sys

import pytest
from PySide6.QtCore import QObject, Signal

pytestmark = pytest.mark.gui


class _Sender(QObject):
    fired = Signal(int)


def test_signals_to_python_slots_keep_reference_counts(qapp):
    sender = _Sender()
    got = []
    sender.fired.connect(got.append)
    before = sys.getrefcount(True), sys.getrefcount(False)
    for i in range(200):
        sender.fired.emit(i)
    assert len(got) == 200
    after = sys.getrefcount(True), sys.getrefcount(False)
    assert after[0] >= before[0] - 5 and after[1] >= before[1] - 5
