"""What the renderer derives at a cost (the light tables' sums, the ground's sink) is kept on disk
by content (render/derived_cache.py): the next run, and the designer's other render process,
read it instead of building it again; a process never builds what another is building; and a
file that is not whole, not ours or of other code is never used."""

from __future__ import annotations

import os
import threading

import numpy as np
import pytest

from core.canopy import Canopy
from core.lighting import Lighting
from core.params import PatchParams
from core.patch import generate_patch
from core.slopes import slope_ratios
from render import derived_cache, facing


def _canopy(alpha: float) -> Canopy:
    stack = np.zeros((2, 8, 4, 4), np.float32)
    stack[..., 3] = alpha
    return Canopy.of([stack], 0.3)


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """A cache folder of the test's own, and a process that has kept nothing in memory."""
    monkeypatch.setenv(derived_cache.CACHE_ENV, str(tmp_path))
    monkeypatch.delenv(derived_cache.SHARED_DIR_ENV, raising=False)
    monkeypatch.setattr(facing, "_kept", facing.OrderedDict())
    monkeypatch.setattr(facing, "_kept_facing", facing.OrderedDict())
    return tmp_path


def _forget(monkeypatch) -> None:
    """As a new run of Sward: nothing kept in memory."""
    monkeypatch.setattr(facing, "_kept", facing.OrderedDict())
    monkeypatch.setattr(facing, "_kept_facing", facing.OrderedDict())


def _no_builds(monkeypatch) -> None:
    def refuse(*_args, **_kwargs):
        raise AssertionError("built again")

    monkeypatch.setattr(facing, "slope_moments_table", refuse)
    monkeypatch.setattr(facing, "facing_moments", refuse)


def test_a_later_run_reads_the_sums_an_earlier_one_built(cache, monkeypatch):
    patch = generate_patch(PatchParams(blade_count=200, seed=3))
    canopy = _canopy(0.4)
    light = Lighting(sun_azimuth=200.0)
    built = facing.kept_slope_moments(patch, canopy)
    built_facing = facing.kept_facing_moments(patch, canopy)
    assert len(list(cache.glob("slope-*.npz"))) == 1
    assert len(list(cache.glob("facing-*.npz"))) == 1

    _forget(monkeypatch)
    _no_builds(monkeypatch)
    read = facing.kept_slope_moments(patch, canopy)
    read_facing = facing.kept_facing_moments(patch, canopy)
    assert read is not None and read_facing is not None
    np.testing.assert_allclose(
        slope_ratios(read, light.sun_direction, 0.3),
        slope_ratios(built, light.sun_direction, 0.3),
        atol=1e-5,
    )
    np.testing.assert_allclose(
        read_facing.lit(light.sun_direction, 0.3),
        built_facing.lit(light.sun_direction, 0.3),
        atol=1e-5,
    )
    # another patch or canopy is never handed these
    other = generate_patch(PatchParams(blade_count=200, seed=4))
    with pytest.raises(AssertionError, match="built again"):
        facing.kept_slope_moments(other, canopy)
    with pytest.raises(AssertionError, match="built again"):
        facing.kept_facing_moments(patch, _canopy(0.5))


def test_sums_read_ahead_are_those_a_frame_then_asks_for(cache, monkeypatch):
    """A grass type begins reading its kept sums when its slices are made (facing.read_ahead);
    the frame that asks for them takes what was read, the same as a read of its own."""
    patch = generate_patch(PatchParams(blade_count=200, seed=3))
    canopy = _canopy(0.4)
    built = facing.kept_slope_moments(patch, canopy)
    facing.kept_facing_moments(patch, None)
    _forget(monkeypatch)
    _no_builds(monkeypatch)
    reads = []
    real = derived_cache._load
    monkeypatch.setattr(
        derived_cache,
        "_load",
        lambda *a: (
            reads.append((*a, threading.current_thread() is threading.main_thread())) or real(*a)
        ),
    )
    facing.read_ahead(patch, canopy)
    read = facing.kept_slope_moments(patch, canopy)
    assert facing.kept_facing_moments(patch, None) is not None
    # the facing sums seen through the canopy were never kept: built when asked for, not read
    with pytest.raises(AssertionError, match="built again"):
        facing.kept_facing_moments(patch, canopy)
    # each found file was read once, on the reader's thread, ahead of the frame
    for kind, seen in (("slope", canopy), ("facing", None)):
        key = facing._digest(patch, seen)
        assert [r for r in reads if r[:2] == (kind, key)] == [(kind, key, False)]
    assert read is not None
    sun = Lighting().sun_direction
    np.testing.assert_allclose(
        slope_ratios(read, sun, 0.3), slope_ratios(built, sun, 0.3), atol=1e-5
    )


def test_nothing_is_kept_with_the_cache_off(tmp_path, monkeypatch):
    monkeypatch.setenv(derived_cache.CACHE_ENV, "off")
    monkeypatch.delenv(derived_cache.SHARED_DIR_ENV, raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.setattr(facing, "_kept", facing.OrderedDict())
    assert derived_cache.folder() is None
    facing.kept_slope_moments(generate_patch(PatchParams(blade_count=120)), _canopy(0.3))
    assert not list(tmp_path.rglob("*.npz"))


def test_a_broken_or_foreign_file_is_built_again(cache, monkeypatch):
    patch = generate_patch(PatchParams(blade_count=150, seed=8))
    canopy = _canopy(0.3)
    built = facing.kept_slope_moments(patch, canopy)
    (path,) = cache.glob("slope-*.npz")
    light = Lighting().sun_direction
    for damage in (b"not an npz file", path.read_bytes()[:1000]):
        path.write_bytes(damage)
        _forget(monkeypatch)
        again = facing.kept_slope_moments(patch, canopy)
        np.testing.assert_allclose(
            slope_ratios(again, light, 0.3), slope_ratios(built, light, 0.3), atol=1e-5
        )
    # a file of other code (another fingerprint of core/'s sources) is not read
    key = path.name.split("-")[2].removesuffix(".npz")
    other_code = derived_cache.path_for("slope", key)
    assert other_code == path
    monkeypatch.setattr(derived_cache, "code_fingerprint", lambda: "0" * 16)
    assert derived_cache.load("slope", key) is None


def test_a_process_waits_for_what_another_is_building(cache, monkeypatch):
    """The designer's draft and full processes never build the same sums twice: the one that
    finds the other's claim waits for its file, or (a draft) draws with what it holds."""
    patch = generate_patch(PatchParams(blade_count=150, seed=9))
    canopy = _canopy(0.3)
    key = facing._digest(patch, canopy)
    made = facing.facing_moments(patch.vertices["normal"])
    path = derived_cache.path_for("facing", key)
    assert path is not None
    claim = path.with_name(f".{path.name}.claim")
    claim.write_text(str(os.getppid()))  # a live process (pytest's parent) is building them

    assert derived_cache.fetch("facing", key, lambda: made, wait=False) is None
    writer = threading.Timer(0.2, lambda: derived_cache.save("facing", key, made))
    writer.start()
    calls = []
    found = derived_cache.fetch("facing", key, lambda: calls.append(1) or made, wait=True)
    writer.join()
    assert not calls  # read, not built
    np.testing.assert_allclose(found.total, made.total, rtol=1e-6)

    # a claim whose process is gone is taken over
    path.unlink()
    claim.write_text("999999999")
    again = derived_cache.fetch("facing", key, lambda: calls.append(1) or made, wait=True)
    assert calls == [1] and again is made and not claim.exists()


def test_a_draft_without_sums_draws_ones_and_refines_once_another_has_built_them(
    ctx, cache, monkeypatch
):
    from render.facing import SlopeTable

    patch = generate_patch(PatchParams(blade_count=150, seed=10))
    canopy = _canopy(0.3)
    light = Lighting(sun_azimuth=120.0)
    table = SlopeTable(ctx, lambda: patch, lambda: canopy)
    try:
        key = facing._digest(patch, canopy)
        path = derived_cache.path_for("slope", key)
        claim = path.with_name(f".{path.name}.claim")
        claim.write_text(str(os.getppid()))  # the full process is building them
        table.use(light, draft=True)
        drawn = np.frombuffer(table.texture.read(), np.float32)
        assert np.all(drawn == 1.0) and table.stale()
        table.refresh(wait=False)  # the draft process does not build them too
        assert table.stale()

        v = patch.vertices
        sums = facing.slope_moments_table(v["normal"], v["position"], v["root"], canopy)
        derived_cache.save("slope", key, sums)
        claim.unlink()
        table.refresh(wait=False)
        assert not table.stale()
        table.use(light, draft=True)
        drawn = np.frombuffer(table.texture.read(), np.float32)
        expected = slope_ratios(sums, light.sun_direction, light.translucency)
        np.testing.assert_allclose(drawn, expected.reshape(-1), atol=1e-5)
    finally:
        table.release()


def test_the_ground_sink_is_read_back_for_the_same_heights(ctx, cache, monkeypatch):
    from core.design_maps import DesignMaps
    from core.ground_mesh import mesh_sink
    from core.heights import hills
    from render import design_maps
    from render.design_maps import DesignMapTextures

    maps = DesignMaps(48, 48)
    maps.write("height", 0, 0, hills(48, seed=4))
    first = DesignMapTextures(ctx, maps)
    sink, quads = first.mesh_sink()
    made = np.frombuffer(sink.read(), np.float32).copy()
    first.release()

    monkeypatch.setattr(design_maps, "mesh_sink", lambda *_a: (_ for _ in ()).throw(
        AssertionError("built again")))  # fmt: skip
    second = DesignMapTextures(ctx, maps)
    try:
        sink, _ = second.mesh_sink()
        assert np.array_equal(np.frombuffer(sink.read(), np.float32), made)
        # an edit still redoes its rows from the kept per-quad excess
        maps.write("height", 10, 20, np.full((4, 20), 1.0, np.float32))
        second.use()
        expected, _ = mesh_sink(maps.layer("height")[..., 0], quads)
        drawn = np.frombuffer(sink.read(), np.float32).reshape(quads[1] + 1, quads[0] + 1)
        assert np.array_equal(drawn, expected)
    finally:
        second.release()


def test_the_folder_keeps_its_newest_files_within_its_size(cache, monkeypatch):
    monkeypatch.setattr(derived_cache, "MAX_BYTES", 150_000)  # about one facing file
    for seed in range(3):
        patch = generate_patch(PatchParams(blade_count=100, seed=20 + seed))
        facing.kept_facing_moments(patch, None)
    (kept,) = cache.glob("facing-*.npz")
    assert kept.name.endswith(f"-{facing._digest(patch, None)}.npz")  # the newest
