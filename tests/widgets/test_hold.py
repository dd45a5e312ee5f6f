"""View → Hold frame rate…: adaptive LOD in the window, driven through its menu action."""

import pytest

from tests.widgets.conftest import wait_full

pytestmark = pytest.mark.gui


def test_holding_a_shorter_frame_slides_every_zone_in_and_off_again(window, qtbot, monkeypatch):
    # a target far below any frame drives the factor to its floor, where it stays: the zones
    # settle within three frames however busy the machine is (a target the frames come near
    # keeps the factor moving with the machine's load, and the window never settles)
    monkeypatch.setattr("core.hold.FACTOR_LIMITS", (0.7, 4.0))
    vp = window.viewport
    wait_full(window)
    vp.request_frame(draft=False)  # a frame after the first (which compiles and converts)
    wait_full(window)
    before = vp.last_stats
    asked = []

    def ask_number(title, label, value, low, high, unit=""):
        asked.append(value)
        return before.t_a_ms * 0.01

    monkeypatch.setattr(window.dialogs, "ask_number", ask_number)
    window.hold_action.trigger()
    assert window.hold_action.isChecked() and asked == [pytest.approx(before.t_a_ms)]
    qtbot.waitUntil(lambda: vp.zone_scale.factor == 0.7, timeout=60000)
    wait_full(window)
    assert vp.renderer_facts()["lod_scale"] == pytest.approx(vp.zone_scale.factor)
    assert vp.renderer_facts(role="draft")["lod_scale"] == pytest.approx(vp.zone_scale.factor)
    assert f"zones ×{vp.zone_scale.factor:.2f}" in window.status.text()
    assert vp.last_stats.c_g < before.c_g  # the geometry zone drew in
    window.hold_action.trigger()  # off: the zones as set
    assert vp.zone_scale.factor == 1.0 and "holding" not in window.status.text()
    wait_full(window)
    assert vp.renderer_facts()["lod_scale"] == 1.0
    assert vp.last_stats.c_g == before.c_g


def test_cancelling_the_target_leaves_hold_frame_rate_off(window, monkeypatch):
    monkeypatch.setattr(window.dialogs, "ask_number", lambda *a, **k: None)
    window.hold_action.trigger()
    assert not window.hold_action.isChecked() and window.viewport.zone_scale.hold is None
