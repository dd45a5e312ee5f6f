"""The Quality view keeps its all-geometry frame: LOD settings do not change it, so after a
zone edit only the LOD frame is drawn again; a change to what the grass looks like (the sun)
draws a new one."""

import pytest

from core.tuning import Knobs, tuned
from tests.widgets.conftest import wait_full
from tests.widgets.test_designer import wait_for_slices

pytestmark = pytest.mark.gui


@pytest.fixture
def own_cache(tmp_path, monkeypatch):
    """A cache of this test's own (the window tests share one, tests/widgets/conftest.py): the
    first Quality view finds no all-geometry frame kept by another test."""
    monkeypatch.setenv("SWARD_CACHE", str(tmp_path / "cache"))


@pytest.mark.usefixtures("own_cache")  # before the window's render processes start
def test_after_a_zone_edit_the_quality_view_reuses_its_all_geometry_frame(window, qtbot):
    vp = window.viewport
    wait_for_slices(window, qtbot)
    window.quality_action.trigger()
    qtbot.waitUntil(lambda: vp.quality_figures is not None, timeout=120000)
    first = vp.quality_figures
    assert not first["reference_kept"]
    assert "kept from before" not in window.status.text()

    # the geometry zone half as deep: more of the frame is volume and image-based grass
    lod = tuned(window.document.lod(0), Knobs(near=0.5))
    window.lod_panel.lod_edited.emit(0, lod)
    qtbot.waitUntil(lambda: vp.quality_figures not in (None, first), timeout=120000)
    again = vp.quality_figures
    assert again["reference_kept"]
    assert again["geometry_ms"] == pytest.approx(first["geometry_ms"], rel=1e-3)
    assert again["lod"]["flip_quarter"] != first["lod"]["flip_quarter"]  # the new zones' figure
    assert "all-geometry frame kept from before" in window.status.text()

    # the sun lower: every frame, all-geometry included, is lit anew
    window.light_panel.root.child("sun_elevation").setValue(
        window.document.light.sun_elevation - 20.0
    )
    qtbot.waitUntil(lambda: vp.quality_figures not in (None, again), timeout=120000)
    assert not vp.quality_figures["reference_kept"]
    window.quality_action.trigger()
    wait_full(window)
