"""The ground mesh under hilly grass (thesis 6.4.4): its triangles are chords of the height
map's surface, and in hollows a chord rises over the ground the grass stands on and would hide
the grass (bare patches in the landscape's volume zone). Sunk by core/ground_mesh.py mesh_sink,
the mesh lies under the grass everywhere."""

import dataclasses

import numpy as np

from app.scenes import get_scene
from core import ground_mesh
from core.camera import Camera
from core.heights import hills
from core.lod import LodConfig, LodLevel

BASE = get_scene("patch-grid")
# rolling hills over 64 × 64 cells; the mesh held to 8 quads a side (as a large terrain's mesh
# spans many cells a quad), so that its chords across the hollows rise over the surface by
# more than the grass is tall
SCENE = dataclasses.replace(
    BASE,
    grid=(64, 64),
    height_map=lambda w, h: hills(64, seed=11, period=2)[:h, :w],
    height_scale=12.0,
    map_size=(64, 64),
    lod=LodConfig((LodLevel("volume", 0.0, None, slices=4, macro=4, max_unplanarity=8.0),)),
)
CAMERA = Camera.from_eye_target((0.0, 16.0, 40.0), (0.0, 4.0, 0.0), fov_y=50.0)


def bare_share(headless, monkeypatch, sink: bool) -> float:
    """The share of the frame where the soil under the grass shows (drawn magenta)."""
    monkeypatch.setattr(ground_mesh, "MESH_LIMIT", 8)
    renderer = headless(SCENE.document(), mode="volume")
    renderer.pipeline.ground.under_grass = (1.0, 0.0, 1.0)
    if not sink:  # the chords as they are: every vertex on the surface
        maps = renderer.pipeline.map_textures
        texture, _ = maps.mesh_sink()
        texture.write(np.zeros(texture.width * texture.height, np.float32).tobytes())
    image, _ = renderer.render(CAMERA, (240, 160))
    rgb = image.astype(np.int32)
    magenta = (rgb[..., 0] - rgb[..., 1] > 60) & (rgb[..., 2] - rgb[..., 1] > 60)
    return float(magenta.mean())


def test_sunk_ground_mesh_lets_the_grass_in_hollows_show(headless, monkeypatch):
    chords = bare_share(headless, monkeypatch, sink=False)
    sunk = bare_share(headless, monkeypatch, sink=True)
    assert chords > 0.02  # the case shows the defect when the mesh is not sunk
    assert sunk < 0.25 * chords


def test_a_height_stroke_redoes_the_sink_of_the_rows_it_reaches(ctx):
    from core.design_maps import DesignMaps
    from core.ground_mesh import mesh_sink, mesh_size
    from render.design_maps import DesignMapTextures

    maps = DesignMaps(48, 48)
    maps.write("height", 0, 0, hills(48, seed=4))
    textures = DesignMapTextures(ctx, maps)
    try:
        sink, quads = textures.mesh_sink()
        assert quads == mesh_size((48, 48))
        # a stroke: a ridge across part of the map
        maps.write("height", 10, 20, np.full((4, 20), 1.0, np.float32))
        textures.use()  # the next frame uploads what changed
        drawn = np.frombuffer(sink.read(), np.float32).reshape(quads[1] + 1, quads[0] + 1)
        expected, _ = mesh_sink(maps.layer("height")[..., 0], quads)
        assert np.array_equal(drawn, expected)
    finally:
        textures.release()


def test_chunked_mesh_is_the_grid_with_skirts_along_inner_chunk_edges():
    from core.ground_mesh import chunked_mesh, grid_mesh

    verts, indices, ranges = chunked_mesh(12, 8, 4)
    grid_verts, grid_indices = grid_mesh(12, 8)

    def triangles(v, i):
        corners = np.round(v.astype(np.float64) * 1e4).astype(np.int64)
        return {tuple(map(tuple, corners[t].tolist())) for t in i.reshape(-1, 3)}

    drawn = triangles(verts, indices)
    grid = triangles(np.c_[grid_verts, np.zeros(len(grid_verts))], grid_indices)
    assert grid <= drawn
    skirts = drawn - grid
    # 2 triangles a quad edge along each inner chunk line (3 lines of 12 quads across v, 3 of
    # 8 across u), drawn from both sides of the line
    assert len(skirts) == 2 * (3 * 12 + 3 * 8)
    assert indices.size // 3 == len(grid_indices) // 3 + 2 * len(skirts)
    # each hangs down, but not below the grid's outer border: there a skirt's end would show
    # below the terrain's edge from outside
    for t in skirts:
        dropped = [c for c in t if c[2] == 10_000]
        assert dropped or len(set(t)) < 3  # (a skirt's last triangle at the border is empty)
        assert all(0 < c[0] < 10_000 and 0 < c[1] < 10_000 for c in dropped)
    # each chunk's run of indices follows the one before; each reaches only its own vertices
    flat = ranges.reshape(-1, 2)
    assert np.array_equal(flat[1:, 0], np.cumsum(flat[:-1, 1]))
    for first, count in flat:
        run = indices[first : first + count]
        assert run.max() - run.min() < len(verts) // 8


# gentler hills over a finer map: far away its mesh's chunks may be coarser
GENTLE = dataclasses.replace(
    SCENE,
    height_map=lambda w, h: hills(256, seed=11, period=2)[:h, :w],
    height_scale=3.0,
    map_size=(256, 256),
)


def _ground_only(headless, forced=None, monkeypatch=None):
    """The hills of GENTLE without grass (density 0), each chunk at its level or at `forced`."""
    import render.ground

    if forced is not None:
        levels = render.ground.chunk_levels

        def fixed(lo, hi, deviation, frame):
            drawn = levels(lo, hi, deviation, frame)
            return np.where(drawn < 0, drawn, forced)

        monkeypatch.setattr(render.ground, "chunk_levels", fixed)
    doc = GENTLE.document()
    doc.density = 0.0
    renderer = headless(doc, mode="lod")
    camera = Camera.from_eye_target((0.0, 14.0, 44.0), (0.0, 2.0, -20.0), fov_y=50.0)
    image, _ = renderer.render(camera, (320, 240))
    return image.astype(np.float32) / 255.0, renderer.pipeline.ground.chunks_drawn


def test_ground_chunks_coarsen_far_away_and_show_the_finest_level_s_ground(headless, monkeypatch):
    """Far chunks take coarser levels (their triangles a few pixels each on the finest), the
    chunks behind the eye none; the ground moves by under a pixel and shows no cracks between
    chunks of different levels (the skirts)."""
    from core.ground_mesh import mesh_levels

    assert len(mesh_levels(GENTLE.map_size)) > 1
    lod, drawn = _ground_only(headless)
    finest, _ = _ground_only(headless, forced=0, monkeypatch=monkeypatch)
    levels = drawn[drawn >= 0]
    assert levels.max() > 0 and levels.min() < levels.max()  # nearer chunks finer than far ones
    moved = np.abs(lod - finest).max(axis=-1)
    assert moved.mean() < 0.003
    assert (moved > 0.1).mean() < 0.002  # a crack would show the sky or the plane below


def test_ground_lets_go_of_another_maps_meshes(headless):
    """A document whose maps have another size (a project opened in the same render process)
    draws its own mesh levels; the ground keeps none of the former maps'."""
    from core.ground_mesh import mesh_levels

    renderer = headless(GENTLE.document(), mode="lod")
    camera = Camera.from_eye_target((0.0, 14.0, 44.0), (0.0, 2.0, -20.0), fov_y=50.0)
    renderer.render(camera, (160, 120))
    ground = renderer.pipeline.ground
    assert set(ground.meshes) <= set(mesh_levels(GENTLE.map_size))
    other = SCENE.document()  # 64 × 64 maps against 256 × 256
    renderer.pipeline.set_design_maps(other.maps)
    renderer.render(camera, (160, 120))
    assert ground.meshes and set(ground.meshes) <= set(mesh_levels(SCENE.map_size))
