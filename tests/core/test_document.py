"""The document: one evented model of the open project that survives save -> load unchanged."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from app.scenes import SCENES
from core.design_maps import LAYERS, DesignMaps
from core.document import MAIN_GRASS, CameraSpec, Document, GrassType, Prop, TerrainSpec
from core.lighting import Lighting
from core.lod import LodConfig, LodLevel
from core.paint_rule import PaintRule
from core.params import PRESETS, SLICE_COUNTS, PatchParams, SliceParams
from core.project_file import load_project, save_project
from core.species import Species, SpeciesTuning

finite = st.floats(-500.0, 500.0, allow_nan=False, width=32)
unit = st.floats(0.0, 1.0, allow_nan=False)
vec3 = st.tuples(finite, finite, finite)
colour = st.tuples(unit, unit, unit)


@st.composite
def params(draw) -> PatchParams:
    base = draw(st.sampled_from(list(PRESETS.values())))
    low = draw(st.floats(0.01, 0.5))
    high = low + draw(st.floats(0.0, 0.5))
    return base.replace(
        blade_count=draw(st.integers(1, 5000)),
        length_min=low,
        length_max=high,
        patch_height=max(base.patch_height, high),
        tilt_max=base.tilt_min + draw(st.floats(0.0, 85.0 - base.tilt_min)),
        bending=draw(st.floats(0.0, 0.95)),
        subdivisions=draw(st.integers(1, 16)),
        clustered=draw(st.booleans()),
        tip_color=draw(colour),
        seed=draw(st.integers(0, 2**31 - 1)),
    )


@st.composite
def lods(draw) -> LodConfig:
    g = draw(st.floats(1.0, 50.0))
    v = g + draw(st.floats(1.0, 50.0))
    return LodConfig(
        (
            LodLevel("geometry", 0.0, g),
            LodLevel(
                "volume",
                g * draw(st.floats(0.3, 0.9)),
                v,
                slices=draw(st.sampled_from(SLICE_COUNTS)),
                macro=draw(st.sampled_from((1, 2, 4, 8))),
            ),
            LodLevel(
                "image",
                g + (v - g) * draw(st.floats(0.1, 0.9)),
                None,
                macro=draw(st.sampled_from((1, 16))),
                max_unplanarity=draw(st.none() | st.floats(0.1, 5.0)),
            ),
        ),
        epsilon=draw(st.floats(0.0, 0.3)),
        silhouettes=draw(st.booleans()),
        view_height=draw(st.none() | st.floats(16.0, 16384.0)),
    )


cameras = (
    st.tuples(vec3, vec3, st.floats(10.0, 5000.0), st.floats(0.001, 1.0))
    .filter(lambda c: c[0] != c[1])
    .map(lambda c: CameraSpec(*c))
)


@st.composite
def documents(draw) -> Document:
    count = draw(st.integers(1, 4))
    grass = [
        GrassType(MAIN_GRASS if i == 0 else f"type {i}", draw(params()), draw(lods()), i)
        for i in range(count)
    ]
    w, h = draw(st.integers(1, 9)), draw(st.integers(1, 9))
    n = w * h * 4
    stack = [  # every map within the range a project file allows (core/project_file.py)
        v
        for layer in LAYERS
        for v in draw(st.lists(st.floats(0.0, layer.top, width=32), min_size=n, max_size=n))
    ]
    maps = DesignMaps.from_stack(np.array(stack, np.float32).reshape(len(LAYERS), h, w, 4))
    named = draw(
        st.dictionaries(st.text("abcxyz ", min_size=1, max_size=8), cameras, min_size=1, max_size=4)
    )
    return Document(
        draw(st.text(max_size=20)),
        grass,
        TerrainSpec(
            draw(st.integers(1, 64)),
            draw(st.integers(1, 64)),
            draw(st.none() | st.integers(0, 1000)),
            draw(st.floats(0.0, 100.0)),
        ),
        maps,
        description=draw(st.text(max_size=40)),
        density=draw(unit),
        slices=SliceParams(
            draw(st.sampled_from(SLICE_COUNTS)),
            draw(st.sampled_from((64, 256))),
            draw(st.sampled_from((16, 64))),
            draw(st.sampled_from((64, 512))),
        ),
        light=Lighting(
            sun_elevation=draw(st.floats(-10.0, 90.0)),
            sun_azimuth=draw(st.floats(0.0, 360.0)),
            sun_color=draw(colour),
            translucency=draw(unit),
            fog_distance=draw(st.floats(1.0, 5000.0)),
        ),
        cameras=named,
        default_camera=draw(st.sampled_from(sorted(named))),
        paths=draw(
            st.dictionaries(
                st.text("pq", min_size=1, max_size=3),
                st.lists(cameras, min_size=2, max_size=3).map(tuple),
                max_size=2,
            )
        ),
        props=tuple(
            draw(
                st.lists(
                    st.builds(
                        Prop,
                        st.tuples(finite, finite),
                        st.tuples(*[st.floats(0.01, 10.0)] * 3),
                        colour,
                        st.floats(0.0, 10.0),
                    ),
                    max_size=3,
                )
            )
        ),
    )


@settings(
    max_examples=60,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(documents())
def test_a_document_survives_save_and_load_unchanged(tmp_path, doc):
    path = tmp_path / "p.sward"
    save_project(path, doc)
    loaded = load_project(path)
    assert loaded.same_as(doc)
    save_project(path, loaded)  # and again: nothing drifts
    assert load_project(path).same_as(doc)


@pytest.mark.parametrize("name", sorted(SCENES))
def test_every_built_in_scene_survives_save_and_load(tmp_path, name):
    doc = SCENES[name].document()
    save_project(tmp_path / "p.sward", doc)
    assert load_project(tmp_path / "p.sward").same_as(doc)


def test_a_change_is_announced_once_and_only_when_it_changes_something():
    doc = SCENES["patch-grid"].document()
    seen = []
    for name in ("params", "lod", "density", "slices", "light", "cameras"):
        getattr(doc.events, name).connect(lambda *args, n=name: seen.append((n, args)))
    doc.density = doc.density
    doc.set_params(0, doc.params(0))
    doc.light = doc.light
    assert seen == []
    doc.density = 0.5
    doc.set_params(0, doc.params(0).replace(blade_count=10))
    doc.set_lod(0, LodConfig.zones(geometry_end=1.0, volume_end=2.0))
    doc.slices = SliceParams(slices=2)
    doc.light = Lighting(sun_elevation=10.0)
    doc.cameras = {**doc.cameras, "mine": CameraSpec((1.0, 2.0, 3.0), (0.0, 0.0, 0.0))}
    assert [n for n, _ in seen] == ["density", "params", "lod", "slices", "light", "cameras"]
    assert doc.params(0).blade_count == 10
    assert doc.lod(0) == LodConfig.zones(geometry_end=1.0, volume_end=2.0)
    assert seen[0][1] == (0.5,) and seen[1][1] == (0, doc.params(0))


def test_impossible_documents_are_refused_with_the_rule():
    doc = SCENES["patch-grid"].document()
    with pytest.raises(ValueError, match="density"):
        doc.density = 1.5
    with pytest.raises(ValueError, match="default camera"):
        doc.cameras = {}
    kinds = [GrassType("a", PatchParams()), GrassType("b", PatchParams())]
    with pytest.raises(ValueError, match="share one density channel"):
        Document("x", kinds, TerrainSpec(2, 2), DesignMaps(4))
    with pytest.raises(ValueError, match="each side"):
        TerrainSpec(0, 4)


def test_the_terrain_follows_the_height_map_only_when_rebuilt():
    doc = SCENES["meadow"].document()
    terrain = doc.terrain
    assert doc.terrain is terrain  # built once
    rebuilt = []
    doc.events.terrain.connect(rebuilt.append)
    doc.maps.fill("height", 1.0)
    assert doc.terrain is terrain
    new = doc.rebuild_terrain()
    assert rebuilt == [new] and new is not terrain
    assert new.cell_max.min() > terrain.cell_max.min()


def test_new_heights_keep_the_cameras_above_the_ground():
    from app.scenes import get_scene

    doc = get_scene("meadow").document()
    w, h = doc.maps.size
    cameras = doc.cameras
    above = {n: c.eye[1] - doc.ground_at(c.eye[0], c.eye[2]) for n, c in cameras.items()}
    ramp = np.tile(np.linspace(0.0, 1.0, w, dtype=np.float32), (h, 1))[..., None]
    doc.set_heights(ramp, 20.0)
    assert doc.terrain_spec.height_scale == 20.0
    assert np.allclose(doc.maps.layer("height")[..., 0], ramp[..., 0])
    for name, c in doc.cameras.items():
        old = cameras[name]
        assert c.eye[1] - doc.ground_at(c.eye[0], c.eye[2]) == pytest.approx(above[name], abs=1e-4)
        # eye and target moved together: the view's direction is the same
        assert np.allclose(np.subtract(c.target, c.eye), np.subtract(old.target, old.eye))
    key = doc.paths["walk"][0]
    assert key.eye[1] - doc.ground_at(key.eye[0], key.eye[2]) > 1.0
    assert doc.terrain.cell_max.max() > 15.0  # the quadtree follows the new ground


def _replica(doc: Document) -> Document:
    """A copy built from the project data and following `doc` through its one event relay,
    as each render process follows the window's document (render/render_client.py)."""
    from core.project_file import document_data, document_from_data

    copy = document_from_data(document_data(doc), doc.maps.stack.copy())

    def follow(info) -> None:
        name = info.signal.name
        if name == "terrain":
            copy.maps.stack[:] = doc.maps.stack  # the maps travel apart from the events
        copy.apply(name, () if name == "terrain" else tuple(info.args))

    doc.events.all.connect(follow)
    return copy


def _every_field_kind(doc: Document) -> list:
    """One change of each kind of document field, as the designer's panels make them."""
    rock = Prop((1.0, 2.0), (0.5, 0.4, 0.5), (0.4, 0.4, 0.4), 0.0, "rock")
    spec = CameraSpec((3.0, 4.0, 5.0), (0.0, 0.0, 0.0))
    other = next(name for name in doc.cameras if name != doc.default_camera)
    return [
        ("params", lambda: doc.set_params(0, doc.params(0).replace(blade_count=77))),
        ("lod", lambda: doc.set_lod(0, LodConfig.zones(geometry_end=3.0, volume_end=9.0))),
        ("density", lambda: setattr(doc, "density", 0.3)),
        ("slices", lambda: setattr(doc, "slices", SliceParams(slices=2))),
        ("light", lambda: setattr(doc, "light", Lighting(sun_elevation=20.0))),
        ("wind", lambda: setattr(doc, "wind", doc.wind.replace(gust_strength=0.7))),
        ("cameras", lambda: setattr(doc, "cameras", {**doc.cameras, "mine": spec})),
        ("default_camera", lambda: setattr(doc, "default_camera", other)),
        ("paths", lambda: setattr(doc, "paths", {**doc.paths, "loop": (spec, spec)})),
        ("props", lambda: setattr(doc, "props", (*doc.props, rock))),
        ("name", lambda: setattr(doc, "name", "renamed")),
        ("description", lambda: setattr(doc, "description", "a field")),
        ("species", lambda: setattr(doc, "species", Species(soil=SpeciesTuning(exponent=9.0)))),
        ("paint_rule", lambda: setattr(doc, "paint_rule", PaintRule(slope=(0.0, 20.0)))),
        ("terrain", lambda: doc.set_heights(doc.maps.layer("height") + 0.25, 4.0)),
    ]


@pytest.mark.parametrize("kind", [k for k, _ in _every_field_kind(SCENES["meadow"].document())])
def test_a_copy_follows_every_field_through_one_relay(kind):
    doc = SCENES["meadow"].document()
    copy = _replica(doc)
    names = []
    doc.events.all.connect(lambda info: names.append(info.signal.name))
    dict(_every_field_kind(doc))[kind]()
    assert names and (kind in names or kind == "terrain")
    assert copy.same_as(doc)
    assert np.array_equal(copy.prop_boxes(), doc.prop_boxes())


def test_every_field_has_its_event_and_the_copy_refuses_unknown_ones():
    from core.document import FIELDS

    doc = SCENES["patch-grid"].document()
    for name in FIELDS:
        assert name in list(doc.events)
    with pytest.raises(ValueError, match="no document field"):
        doc.apply("maps", ())
