"""A draft after a blade edit does not wait for the new patch's light sums (render/facing.py):
the sums held stand in until the full frame, which builds them and draws what a renderer that
never saw the old patch draws. A draft's blades have fewer segments and look the same at its
size."""

import numpy as np
import pytest

from app.scenes import get_scene

SIZE = (240, 160)


@pytest.fixture(autouse=True)
def sums_built_here(monkeypatch):
    """These tests watch when a renderer builds its sums: none read from the run's folder."""
    monkeypatch.setenv("SWARD_CACHE", "off")


def test_a_blade_edits_draft_keeps_the_sums_and_its_full_frame_builds_them(headless, monkeypatch):
    import render.facing as facing

    doc = get_scene("meadow").document()
    camera = doc.camera()
    renderer = headless(doc)
    renderer.render(camera, SIZE)  # the sums of the patch as it is
    built = []
    for name in ("facing_moments", "slope_moments_table"):
        real = getattr(facing, name)
        monkeypatch.setattr(
            facing,
            name,
            lambda *a, _real=real, _name=name, **k: built.append(_name) or _real(*a, **k),
        )
    params = doc.grass_types[0].params
    doc.set_params(0, params.replace(length_min=params.length_min * 1.1))
    renderer.render(camera, SIZE, half_resolution=True)
    assert built == []  # the draft drew with the sums it held
    assert renderer.pipeline.stale_light_sums()  # and says so: the draft process refines
    full, _ = renderer.render(camera, SIZE)
    assert not renderer.pipeline.stale_light_sums()
    assert "facing_moments" in built and "slope_moments_table" in built
    fresh, _ = headless(doc).render(camera, SIZE)
    assert np.abs(full.astype(int) - fresh.astype(int)).max() <= 2  # no sums of the old patch


def test_the_draft_process_refreshes_the_sums_a_draft_lacked(headless):
    doc = get_scene("meadow").document()
    camera = doc.camera()
    renderer = headless(doc)
    renderer.render(camera, SIZE, half_resolution=True)
    params = doc.grass_types[0].params
    doc.set_params(0, params.replace(length_min=params.length_min * 1.1))
    renderer.render(camera, SIZE, half_resolution=True)
    assert renderer.pipeline.stale_light_sums()
    renderer.pipeline.refresh_light_sums()  # render/render_server.py refine_one
    assert not renderer.pipeline.stale_light_sums()
    refined, _ = renderer.render(camera, SIZE, half_resolution=True)
    fresh, _ = headless(doc).render(camera, SIZE, half_resolution=True)
    assert np.abs(refined.astype(int) - fresh.astype(int)).max() <= 2


def test_a_draft_draws_blades_of_fewer_segments_that_look_the_same(headless):
    """A draft draws each blade one segment level coarser than a full frame at its size
    (core/segments.py): fewer triangles, the same picture at that size."""
    from render import context

    doc = get_scene("meadow").document()
    camera = doc.camera()
    renderer = headless(doc)
    pipeline = renderer.pipeline
    size = (200, 150)
    out = renderer._target(size)
    pipeline.render(camera, out, size, draft=False)  # slices and sums made
    drawn, triangles = {}, {}
    for draft in (False, True):
        triangles[draft] = pipeline.render(camera, out, size, draft=draft).triangles
        drawn[draft] = context.read_rgb(out, size, 3).astype(np.int32)
    assert triangles[True] < 0.7 * triangles[False]
    difference = np.abs(drawn[True] - drawn[False])
    assert difference.max() > 0  # the draft drew its own triangles
    assert difference.mean() < 1.5  # on 0 … 255: the same picture at a draft's size
