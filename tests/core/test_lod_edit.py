"""LOD zone editor edits: every result is a valid LodConfig, or a message says why not."""

import pytest

from core.lod import LodConfig
from core.lod_edit import append_level, move_level, remove_level, set_field, set_view_heights

THREE = LodConfig.zones(geometry_end=4.0, volume_end=12.0, transition=2.0)


def test_append_and_remove_keep_the_configuration_valid():
    four = append_level(THREE)
    assert len(four.levels) == 4 and four.levels[-1].end is None
    assert four.levels[2].end is not None and four.levels[3].begin < four.levels[2].end
    assert remove_level(four, 3) == THREE.__class__(
        (*THREE.levels[:2], four.levels[2].__class__("image", THREE.levels[2].begin, None)),
        THREE.epsilon,
    )
    first_gone = remove_level(THREE, 0)
    assert first_gone.levels[0].representation == "volume" and first_gone.levels[0].begin == 0
    middle_gone = remove_level(THREE, 1)
    assert [lv.representation for lv in middle_gone.levels] == ["geometry", "image"]
    with pytest.raises(ValueError, match="only LOD level"):
        remove_level(LodConfig.zones(None, None), 0)


def test_move_swaps_what_levels_draw_not_where():
    moved = move_level(set_field(THREE, 1, "macro", 4), 1, -1)
    assert [lv.representation for lv in moved.levels] == ["volume", "geometry", "image"]
    assert [lv.begin for lv in moved.levels] == [lv.begin for lv in THREE.levels]
    assert moved.levels[1].macro == 1  # geometry draws single cells
    assert moved.levels[0].macro == 4
    with pytest.raises(ValueError):
        move_level(THREE, 0, -1)


def test_an_impossible_end_is_refused_with_the_rule():
    with pytest.raises(ValueError, match=r"volume zone .* must end after the geometry zone"):
        set_field(THREE, 0, "end", 20.0)  # geometry past the volume level's end
    assert set_field(THREE, 1, "end", 20.0).levels[1].end == 20.0


def test_one_view_height_for_every_grass_type_keeps_their_levels():
    from app.scenes import get_scene

    doc = get_scene("meadow").document()  # two grass types with their own levels
    levels = [lod.levels for lod in doc.lods]
    doc.set_lods(set_view_heights(doc.lods, 300))
    assert [lod.view_height for lod in doc.lods] == [300.0, 300.0]
    assert [lod.levels for lod in doc.lods] == levels
    doc.set_lods(set_view_heights(doc.lods, 0))  # 0: world units again
    assert [lod.view_height for lod in doc.lods] == [None, None]
    with pytest.raises(ValueError, match="2 grass types"):
        doc.set_lods(doc.lods[:1])
