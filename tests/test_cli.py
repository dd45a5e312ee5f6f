"""The command line as a user runs it: a real process, its output and exit status."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from app.scenes import get_scene
from tests import cli_process
from tests.conftest import coverage
from tests.project_files import project_parts, write_project


def sward(*args, env=None, fresh=False):
    """`sward ARGS` as a user runs it, keeping its light sums as a user's runs do (between the
    test run's processes: tests/conftest.py kept_sums) unless `env` names SWARD_CACHE. The
    process is forked from one that has done the imports every run repeats
    (tests/cli_process.py); `fresh` starts a new interpreter, `python -m app.cli ARGS`."""
    if env is None:
        env = dict(os.environ)
    if not fresh:
        return cli_process.run(args, env, timeout=240)
    return subprocess.run(
        [sys.executable, "-m", "app.cli", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=240,
    )


def test_render_writes_png_and_stats(tmp_path):
    out, st = tmp_path / "lawn.png", tmp_path / "s.json"
    r = sward(
        "render",
        "--scene",
        "patch-grid",
        "--size",
        "160x120",
        "--eye",
        "3,2,3",
        "--target",
        "0,0,0",
        "--out",
        str(out),
        "--stats",
        str(st),
        fresh=True,  # the one run here from a new interpreter, as a user starts it
    )
    assert r.returncode == 0, r.stderr

    image = np.asarray(Image.open(out))
    assert image.shape == (120, 160, 3)
    assert coverage(image) > 0.3
    data = json.loads(st.read_text())
    for key in ("t_a_ms", "t_g_ms", "c_g", "width", "height", "scene", "fps"):
        assert key in data
    assert (data["width"], data["height"], data["scene"]) == (160, 120, "patch-grid")
    # the scene's LOD zones: every one of the 64 cells drawn, some by two representations
    assert data["c_g"] > 0 and data["c_g"] + data["c_v"] + data["c_i"] >= 64


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--scene", "moon"], ["unknown scene", "moon", "patch-grid"]),
        (["--size", "12by4"], ["malformed size", "12by4"]),
        (["--out", "/no/such/folder/x.png"], ["cannot write", "/no/such/folder"]),
        (["--camera", "drone"], ["unknown camera", "drone"]),
        (["--density", "3"], ["--density", "out of range"]),
        (["--eye", "1,2"], ["malformed point"]),
        (["--time", "soon"], ["malformed time", "soon"]),
        (["--time", "2:1:0.5"], ["time", "STEP"]),
        (["--time", "0:1000:0.01"], ["frames", "at most 10000"]),
        (["--time", "0:1:0.5", "--out", "f%q.png"], ["--out", "pattern"]),
        (["--time", "0:2000:0.5", "--size", "1024x768"], ["--out", "too many", "%d"]),
        (["--wind", "gale"], ["--wind", "gale", "light-breeze, gusty, storm"]),
        (["--blade-reach", "3"], ["--blade-reach", "1 to 2", "'3'"]),
    ],
)
def test_bad_input_is_one_clear_line(tmp_path, args, words):
    if "--out" not in args:
        args = [*args, "--out", str(tmp_path / "x.png")]
    r = sward("render", *args)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr
    last = r.stderr.strip().splitlines()[-1]
    for word in words:
        assert word in last


def test_designer_without_display_explains_headless_rendering():
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    r = sward(env=env)
    assert r.returncode != 0 and "Traceback" not in r.stderr
    assert "no display" in r.stderr and "sward render" in r.stderr


def test_scenes_lists_patch_grid():
    r = sward("scenes")
    assert r.returncode == 0 and "patch-grid" in r.stdout


def test_output_read_by_a_reader_that_stops_early_ends_without_a_traceback():
    """`sward scenes | head -1`: the reader goes away before the listing is written."""
    with subprocess.Popen(
        [sys.executable, "-m", "app.cli", "scenes"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    ) as p:
        p.stdout.close()
        err = p.stderr.read()
        assert p.wait(timeout=120) == 141
    assert "Traceback" not in err and "Exception ignored" not in err, err


def test_profile_prints_the_table_and_the_parts_add_up(tmp_path):
    out = tmp_path / "profile.json"
    r = sward(
        "profile", "--scene", "patch-grid", "--frames", "2", "--size", "160x120", "--out", str(out)
    )
    assert r.returncode == 0, r.stderr
    header = r.stdout.splitlines()[0].split()
    assert header == [
        "viewpoint",
        "fps",
        "t_a",
        "t_q",
        "t_g",
        "t_v",
        "t_i",
        "t_m",
        "t_s",
        "c_g",
        "c_v",
        "c_i",
    ]
    doc = json.loads(out.read_text())
    names = [v["name"] for v in doc["viewpoints"]]
    assert names == ["default", "close", "top", "grazing"]
    for view in doc["viewpoints"]:
        assert len(view["frames"]) == 2 and view["parts_add_up"]
        for frame in view["frames"]:
            parts = sum(
                frame[k]
                for k in ("t_q_ms", "t_u_ms", "t_g_ms", "t_v_ms", "t_i_ms", "t_m_ms", "t_o_ms")
            )
            assert parts <= frame["t_a_ms"] + 0.5
            assert parts >= 0.9 * frame["t_a_ms"] - 3.0
    grazing = doc["viewpoints"][-1]["summary"]
    assert grazing["c_g"]["median"] > 0 and grazing["c_v"]["median"] > 0  # LOD zones in view
    assert "add up to t_a" in r.stdout


def test_profile_along_a_path_and_bad_path(tmp_path):
    out = tmp_path / "frames.csv"
    r = sward(
        "profile", "--scene", "patch-grid", "--path", "orbit", "--frames", "3", "--size", "96x64",
        "--out", str(out),
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "path orbit" in r.stdout
    rows = out.read_text().splitlines()  # the CSV the designer's Record button writes too
    assert rows[0].split(",")[:3] == ["frame", "t_a_ms", "t_q_ms"] and len(rows) == 4
    r = sward("profile", "--scene", "patch-grid", "--path", "nowhere")
    assert r.returncode == 2
    assert "unknown camera path 'nowhere'" in r.stderr and "orbit" in r.stderr
    assert "Traceback" not in r.stderr


def test_new_makes_a_terrain_of_any_size_with_its_maps_resampled(tmp_path):
    from core.project_file import load_project

    path = tmp_path / "wide.sward"
    r = sward("new", str(path), "--scene", "meadow", "--cells", "192x96")
    assert r.returncode == 0, r.stderr
    assert "192 × 96 cells" in r.stdout
    wide, meadow = load_project(path), get_scene("meadow").document()
    assert (wide.terrain.columns, wide.terrain.rows) == (192, 96)
    # the 48 × 48 meadow's 256² maps keep their texels per cell: 1024 × 512
    assert wide.maps.size == (1024, 512)
    # resampled, not cut: the hills and the density stretch with the terrain
    heights, original = wide.maps.layer("height")[..., 0], meadow.maps.layer("height")[..., 0]
    assert abs(float(heights.mean()) - float(original.mean())) < 0.05
    assert wide.terrain.height_scale == meadow.terrain.height_scale
    for bad, message in (("40x", "malformed terrain size"), ("5000x5000", "out of range")):
        r = sward("new", str(tmp_path / "x.sward"), "--scene", "meadow", "--cells", bad)
        assert r.returncode == 2 and message in r.stderr and "Traceback" not in r.stderr
    assert not (tmp_path / "x.sward").exists()


def test_new_writes_a_project_that_render_reads(tmp_path):
    path = tmp_path / "field.sward"
    r = sward("new", str(path), "--scene", "patch-grid")
    assert r.returncode == 0, r.stderr
    out = tmp_path / "p.png"
    r = sward("render", "--project", str(path), "--size", "96x64", "--out", str(out))
    assert r.returncode == 0, r.stderr
    with Image.open(out) as image:
        assert image.size == (96, 64)
    bad = tmp_path / "bad.sward"
    bad.write_text("not a project")
    r = sward("render", "--project", str(bad), "--out", str(out))
    assert r.returncode == 2
    assert "bad.sward" in r.stderr and "not a zip file" in r.stderr
    assert "Traceback" not in r.stderr


def test_new_saves_the_winds_blade_reach(tmp_path):
    from core.project_file import load_project

    path = tmp_path / "gusty.sward"
    r = sward("new", str(path), "--scene", "patch-grid", "--wind", "on", "--blade-reach", "1.5")
    assert r.returncode == 0, r.stderr
    wind = load_project(path).wind
    assert wind.enabled and wind.blade_reach == 1.5


def test_a_wind_preset_on_the_command_line_blows_with_its_values(tmp_path):
    from core.project_file import load_project
    from core.wind import PRESETS, Wind

    path = tmp_path / "storm.sward"
    r = sward("new", str(path), "--scene", "patch-grid", "--wind", "light-breeze")
    assert r.returncode == 0, r.stderr
    wind = load_project(path).wind
    assert wind.enabled and wind.gust_strength == PRESETS["light breeze"]["gust_strength"]
    assert wind.direction == Wind().direction  # the scene's direction kept


def test_negative_coordinates_work_as_written(tmp_path):
    out, st = tmp_path / "hill.png", tmp_path / "hill.json"
    r = sward(
        "render", "--scene", "patch-grid", "--eye", "-6,2.5,-6", "--target", "-0.5,0,-0.5",
        "--size", "96x64", "--out", str(out), "--stats", str(st),
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert json.loads(st.read_text())["camera"] == "custom"
    with Image.open(out) as image:
        assert coverage(np.asarray(image.convert("RGB"))) > 0.1  # it looks at the grass


def test_a_malformed_project_is_one_line_and_exit_2(tmp_path):

    path = tmp_path / "p.sward"
    assert sward("new", str(path), "--scene", "patch-grid").returncode == 0
    data, maps = project_parts(path)
    data["cameras"][data["default_camera"]]["near"] = -1.0
    write_project(path, data, maps)
    r = sward("render", "--project", str(path), "--out", str(tmp_path / "x.png"))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "p.sward" in lines[0] and ".near" in lines[0], lines


def test_quality_compares_lod_with_all_geometry(tmp_path):
    r = sward(
        "quality", "--scene", "patch-grid", "--camera", "default", "--size", "160x96",
        "--out", str(tmp_path),
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "LOD against all-geometry" in r.stdout
    data = json.loads((tmp_path / "quality.json").read_text())
    (row,) = data["cameras"]
    assert row["camera"] == "default"
    lod, floor = row["lod"], row["floor"]
    # the LOD frame differs from all-geometry, and by more than blade detail alone does
    assert 0 < floor["flip_quarter"] < lod["flip_quarter"] < 0.5
    assert row["over_floor"] == pytest.approx(lod["flip_quarter"] / floor["flip_quarter"])
    assert row["speedup"] > 0 and row["geometry_ms"] > 0
    # the scene's three representations each cover part of the frame
    assert all(row["techniques"][t]["pixels"] > 50 for t in ("geometry", "volume", "image"))
    heat = np.asarray(Image.open(tmp_path / "default-flip.png"))
    assert heat.shape[:2] == (96, 160) and heat.max() > 0
    assert (tmp_path / "default-lod.png").is_file()


def test_quality_estimates_a_reference_beyond_its_budget_and_measures_popping(tmp_path):
    r = sward("quality", "--scene", "patch-grid", "--size", "96x64", "--budget", "1e-6")
    assert r.returncode == 0, r.stderr
    assert "not drawn" in r.stdout and "estimated" in r.stdout
    r = sward(
        "quality", "--scene", "patch-grid", "--path", "orbit", "--frames", "3", "--size", "96x64",
        "--out", str(tmp_path),
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    path = json.loads((tmp_path / "quality.json").read_text())["path"]
    assert path["frames"] == 3 and path["popping"] > 0
    assert path["reference_max_change"] > 0


def test_quality_sweep_writes_each_case_its_checks_and_a_contact_sheet(tmp_path):
    r = sward(
        "quality", "--sweep", "--case", "patch-grid/top", "--case", "football/player",
        "--size", "160x90", "--out", str(tmp_path),
    )  # fmt: skip
    assert r.returncode in (0, 1), r.stderr
    assert "far-field sweep" in r.stdout and "checks over their limits" in r.stdout
    data = json.loads((tmp_path / "sweep.json").read_text())
    rows = {row["case"]: row for row in data["cases"]}
    assert set(rows) == {"patch-grid/top", "football/player"}
    # the patch grid's reference is drawn: its regions' colours are compared with it
    assert rows["patch-grid/top"]["region_colour"]
    # the football's is not (billions of blade triangles), and its hand-over steps are checked
    assert "not drawn" in rows["football/player"]["reference"]
    assert "steps_p95" in rows["football/player"]["checks"]
    assert (r.returncode == 1) == bool(data["failed"])
    sheet = np.asarray(Image.open(tmp_path / "sweep.png"))
    assert sheet.shape[1] == 4 * 80 and sheet.std() > 10


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--sweep", "--case", "nowhere"], "--case nowhere: no sweep case"),
        (["--case", "meadow"], "give --sweep as well"),
        (["--sweep", "--camera", "default"], "--sweep draws the built-in scenes' cameras"),
        (["--camera", "nowhere"], "unknown camera 'nowhere'"),
        (["--path", "nowhere"], "unknown camera path 'nowhere'"),
        (["--frames", "1", "--path", "orbit"], "--frames 1 out of range"),
        (["--budget", "0"], "--budget 0 out of range"),
        (["--time-step", "-1"], "--time-step -1 out of range"),
        (["--time", "0:1:0.5"], "one moment"),
    ],
)
def test_quality_refuses_bad_input_in_one_line(args, words):
    r = sward("quality", "--scene", "patch-grid", *args)
    assert r.returncode == 2
    assert words in r.stderr and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_new_imports_a_16_bit_height_map(tmp_path):
    dem = tmp_path / "dem.png"
    heights = np.tile(np.linspace(0, 65535, 300).astype(np.uint16), (200, 1))  # a ramp along x
    Image.fromarray(heights).save(dem)
    out = tmp_path / "dem.sward"
    r = sward("new", str(out), "--scene", "meadow", "--height-map", str(dem), "--height-scale", "7")
    assert r.returncode == 0, r.stderr
    from core.project_file import load_project

    doc = load_project(out)
    assert doc.terrain_spec.height_scale == 7.0
    h = doc.maps.layer("height")[..., 0]
    assert h[:, 0].max() < 0.01 and h[:, -1].min() > 0.99  # resampled to the project's maps
    assert np.all(np.diff(h[h.shape[0] // 2]) >= -1e-6)
    for c in doc.cameras.values():  # the views were lifted with the ground under them
        assert c.eye[1] > doc.ground_at(c.eye[0], c.eye[2]) + 1.0
    bad = tmp_path / "bad.png"
    bad.write_bytes(b"not an image")
    r = sward("new", str(tmp_path / "x.sward"), "--height-map", str(bad))
    assert r.returncode == 2 and "--height-map: bad.png" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    r = sward("new", str(tmp_path / "x.sward"), "--height-scale", "-1")
    assert r.returncode == 2 and "--height-scale -1 out of range" in r.stderr


def test_lod_distances_for_a_view_height_are_saved_and_draw_geometry_farther(tmp_path):
    path = tmp_path / "p.sward"
    assert sward("new", str(path), "--scene", "meadow", "--lod-view-height", "300").returncode == 0
    from core.project_file import load_project

    doc = load_project(path)
    assert [doc.lod(i).view_height for i in range(len(doc.grass_types))] == [300.0, 300.0]
    counts = {}
    for height in ("none", "48"):  # the frame is 96 px tall: zones twice as far with 48
        stats = tmp_path / f"{height}.json"
        r = sward(
            "render", "--project", str(path), "--size", "160x96", "--lod-view-height", height,
            "--stats", str(stats),
        )  # fmt: skip
        assert r.returncode == 0, r.stderr
        counts[height] = json.loads(stats.read_text())["c_g"]
    assert counts["48"] > 2 * counts["none"] > 0
    r = sward("render", "--size", "160x96", "--lod-view-height", "2", "--stats", str(stats))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "view height '2' out of range" in r.stderr


def test_render_a_time_sequence_of_the_wind(tmp_path):
    """--time FROM:TO:STEP writes one PNG a moment; the grass moves between them with the wind
    on, and stands still with --wind off."""
    common = ["render", "--scene", "patch-grid", "--size", "160x120", "--camera", "grazing"]
    stats = tmp_path / "s.json"
    r = sward(
        *common,
        "--wind",
        "on",
        "--time",
        "0:1:0.5",
        "--out",
        str(tmp_path / "f%04d.png"),
        "--stats",
        str(stats),
    )
    assert r.returncode == 0, r.stderr
    frames = [np.asarray(Image.open(tmp_path / f"f{i:04d}.png")) for i in range(3)]
    assert [f["time"] for f in json.loads(stats.read_text())["frames"]] == [0.0, 0.5, 1.0]
    assert np.any(frames[0] != frames[1]) and np.any(frames[1] != frames[2])
    still = [tmp_path / "still0.png", tmp_path / "still1.png"]
    for seconds, out in zip(("0", "0.5"), still, strict=True):
        r = sward(*common, "--wind", "off", "--time", seconds, "--out", str(out))
        assert r.returncode == 0, r.stderr
    assert np.array_equal(np.asarray(Image.open(still[0])), np.asarray(Image.open(still[1])))
    # without a %d pattern: one animated PNG, a frame per moment
    animation = tmp_path / "gust.png"
    r = sward(*common, "--wind", "on", "--time", "0:1:0.5", "--out", str(animation))
    assert r.returncode == 0, r.stderr
    with Image.open(animation) as apng:
        assert apng.is_animated and apng.n_frames == 3
        apng.seek(2)
        assert np.array_equal(np.asarray(apng.convert("RGB")), frames[2])


def test_render_a_video_of_the_wind(tmp_path):
    """--out NAME.mp4 with a time sequence writes an H.264 video at one frame per step, its
    frames the rendered ones (within the codec's loss), odd sizes padded to even; one moment
    is no video."""
    import imageio_ffmpeg

    common = ["render", "--scene", "patch-grid", "--size", "161x121", "--camera", "grazing"]
    video, first = tmp_path / "gust.mp4", tmp_path / "first.png"
    r = sward(*common, "--wind", "on", "--time", "0:1:0.25", "--out", str(video))
    assert r.returncode == 0, r.stderr
    r = sward(*common, "--wind", "on", "--time", "0", "--out", str(first))
    assert r.returncode == 0, r.stderr
    assert imageio_ffmpeg.count_frames_and_secs(str(video)) == (5, 1.25)  # 4 frames a second
    decode = [imageio_ffmpeg.get_ffmpeg_exe(), "-v", "error", "-i", str(video)]
    raw = subprocess.run(
        [*decode, "-f", "rawvideo", "-pix_fmt", "rgb24", "-"], capture_output=True, check=True
    ).stdout
    assert len(raw) == 5 * 122 * 162 * 3  # five frames of 162 × 122: padded to even
    frames = np.frombuffer(raw, np.uint8).reshape(5, 122, 162, 3)
    rendered = np.asarray(Image.open(first).convert("RGB")).astype(int)
    assert np.abs(frames[0][:121, :161].astype(int) - rendered).mean() < 6.0
    assert np.abs(frames[0].astype(int) - frames[4]).mean() > 0.5  # the grass moved
    r = sward(*common, "--time", "1", "--out", str(tmp_path / "one.mp4"))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "a video needs a time sequence" in r.stderr


def test_quality_along_a_path_while_the_wind_blows(tmp_path):
    """--time-step: each path frame is that much wind later; with the wind on the still camera
    sees the grass move, so the reference changes between frames by more than without."""
    changes, printed = {}, {}
    for wind in ("on", "off"):
        out = tmp_path / wind
        r = sward(
            "quality", "--scene", "patch-grid", "--path", "orbit", "--frames", "3",
            "--size", "96x64", "--wind", wind, "--time", "1", "--time-step", "0.5",
            "--out", str(out),
        )  # fmt: skip
        assert r.returncode == 0, r.stderr
        result = json.loads((out / "quality.json").read_text())
        assert result["wind"] == (wind == "on") and result["time_step"] == 0.5
        changes[wind] = result["path"]["reference_max_change"]
        printed[wind] = r.stdout
    assert "wind at 1 s (+0.5 s a path frame)" in printed["on"]
    assert "wind" not in printed["off"].splitlines()[0]
    assert changes["on"] > changes["off"]


def test_quality_with_the_wind_on_also_measures_against_still_airs_floor(tmp_path):
    """Bent blades show less detail: the wind's floor is lower than still air's. With the wind
    on, quality reports the LOD frame against still air's floor too, which is the floor a run
    with the wind off measures."""
    rows = {}
    for wind in ("on", "off"):
        out = tmp_path / wind
        r = sward(
            "quality", "--scene", "patch-grid", "--camera", "grazing", "--size", "160x96",
            "--wind", wind, "--time", "1", "--out", str(out),
        )  # fmt: skip
        assert r.returncode == 0, r.stderr
        (rows[wind],) = json.loads((out / "quality.json").read_text())["cameras"]
        assert ("still air's floor" in r.stdout) == (wind == "on")
    on, off = rows["on"], rows["off"]
    assert "still_floor" not in off
    assert on["still_floor"]["flip_quarter"] == pytest.approx(off["floor"]["flip_quarter"])
    assert on["floor"]["flip_quarter"] != pytest.approx(off["floor"]["flip_quarter"])
    assert on["over_still_floor"] == pytest.approx(
        on["lod"]["flip_quarter"] / off["floor"]["flip_quarter"]
    )
    for t in on["techniques"].values():
        if t["pixels"] and t["still_floor"]:
            assert t["over_still_floor"] == pytest.approx(t["flip_quarter"] / t["still_floor"])


def test_profile_reports_what_the_wind_costs_per_technique(tmp_path):
    out = tmp_path / "p.json"
    args = ["profile", "--scene", "patch-grid", "--frames", "2", "--size", "96x64", "--out"]
    r = sward(*args, str(out), "--wind", "on")
    assert r.returncode == 0, r.stderr
    assert "wind at default: t_a" in r.stdout and "t_v" in r.stdout
    cost = json.loads(out.read_text())["wind_cost"]["default"]
    for part in ("t_a_ms", "t_g_ms", "t_v_ms", "t_i_ms"):
        assert cost[part]["wind"] > 0 and cost[part]["still"] > 0
    r = sward(*args, str(out), "--wind", "off")
    assert r.returncode == 0 and "wind at" not in r.stdout
    assert "wind_cost" not in json.loads(out.read_text())
