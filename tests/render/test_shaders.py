import pytest

from render.shaders import ShaderError, load_program, program_names, stage_source, wind_defines

EXPECTED = {
    "geometry.glsl": {
        "u_view_proj",
        "u_density",
        "u_blade",
        "u_light_dir",
        "in_position",
        "in_threshold",
        "in_origin",
        "in_cell_density",
        "in_mirror",
        "in_config",
        "u_design",
        "u_ao_impact",
    },
    "slice_capture.glsl": {"u_view_proj", "u_clip_lo", "u_clip_hi", "u_blade", "in_threshold"},
    "volume.glsl": {
        "u_view_proj",
        "u_slices",
        "u_side_color",
        "u_side_data",
        "u_design_far",
        "in_corner",
        "in_size",
        "in_mirror",
        "in_config",
        "in_plane",
        "in_rect",
    },
    "image.glsl": {
        "u_view_proj",
        "u_top_color",
        "u_top_data",
        "u_design",
        "in_corner",
        "in_rect",
        "in_size",
        "in_mirror",
        "in_config",
    },
    "ground.glsl": {"u_view_proj", "u_extent", "u_grass_rect", "u_design", "in_corner"},
    "overlay.glsl": {"u_view_proj", "u_color", "in_position"},
    "present.glsl": {"u_frame", "in_corner"},
    "props.glsl": {"u_view_proj", "u_light_dir", "in_position", "in_centre", "in_size"},
}


@pytest.mark.parametrize("name", program_names())
@pytest.mark.parametrize(
    "wind,trampled", [(False, False), (True, False), (False, True), (True, True)],
    ids=["still", "wind", "trampled", "both"],
)  # fmt: skip
def test_every_shader_compiles_with_expected_inputs(ctx, name, wind, trampled):
    program = load_program(ctx, name, wind_defines(wind, trampled))
    assert EXPECTED.get(name, set()) <= set(program)


@pytest.mark.parametrize("name", ["geometry.glsl", "volume.glsl", "image.glsl", "ground.glsl"])
def test_painted_light_maps_are_a_variant_of_their_own(ctx, name):
    """Every program that lights grass or soil by the light maps compiles with LIGHT_MAPS and
    is another program than the one for unpainted maps."""
    lit = load_program(ctx, name, ("LIGHT_MAPS",))
    assert "u_design" in set(lit)
    assert lit is not load_program(ctx, name)


def test_volume_pass_with_the_horizontal_slice_reads_it_and_one_without_does_not(ctx):
    floor = {"u_floor", "u_top_color", "u_top_data", "u_floor_shade", "u_band_column"}
    assert floor <= set(load_program(ctx, "volume.glsl", ("FLOOR",)))
    assert not floor & set(load_program(ctx, "volume.glsl"))


def test_wind_variant_is_its_own_program_and_reads_the_wind(ctx):
    still = load_program(ctx, "geometry.glsl")
    windy = load_program(ctx, "geometry.glsl", wind_defines(True))
    assert windy is not still
    assert windy is load_program(ctx, "geometry.glsl", ("WIND",))
    # still air reads no wind noise; the wind's variant does
    assert "u_wind_noise" not in still and "u_wind_noise" in windy


@pytest.mark.parametrize("name", ["geometry.glsl", "volume.glsl", "image.glsl"])
def test_trampled_grass_reads_the_trample_map_and_no_wind(ctx, name):
    trodden = load_program(ctx, name, wind_defines(False, True))
    assert "u_trample" in trodden and "u_wind_noise" not in trodden
    assert "u_trample" not in load_program(ctx, name)


def test_every_program_is_known():
    assert set(program_names()) == set(EXPECTED)


def test_stage_define_follows_version_line():
    src = stage_source("geometry.glsl", "VERTEX_SHADER").splitlines()
    assert src[0].startswith("#version") and src[1] == "#define VERTEX_SHADER"


def test_missing_shader_names_the_file(ctx):
    with pytest.raises(ShaderError, match=r"nope\.glsl"):
        load_program(ctx, "nope.glsl")
