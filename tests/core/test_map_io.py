"""Map import and export: 8/16-bit greyscale and RGBA PNGs, raw 16-bit heights, resampling,
and bad files refused with a message naming them."""

import os

import numpy as np
import pytest
from PIL import Image

from core.map_io import MapFileError, fit_channels, read_image, read_raw16, resample, write_map


def test_sixteen_bit_greyscale_round_trips_at_full_precision(tmp_path):
    heights = np.linspace(0.0, 1.0, 64 * 32, dtype=np.float32).reshape(32, 64, 1)
    write_map(tmp_path / "h.png", heights)
    back = read_image(tmp_path / "h.png")
    assert back.shape == (32, 64, 1)
    assert np.abs(back - heights).max() <= 0.5 / 65535 + 1e-7  # 16 bits, not 8


def test_eight_bit_grey_and_rgba_read_as_their_channels(tmp_path):
    grey = np.arange(256, dtype=np.uint8).reshape(16, 16)
    Image.fromarray(grey).save(tmp_path / "g.png")
    assert np.allclose(read_image(tmp_path / "g.png")[..., 0], grey / 255.0)
    rgba = np.zeros((8, 8, 4), np.uint8)
    rgba[..., 0], rgba[..., 3] = 255, 128
    Image.fromarray(rgba).save(tmp_path / "c.png")
    colour = fit_channels(read_image(tmp_path / "c.png"), "color", single=False)
    assert colour.shape == (8, 8, 4) and np.allclose(colour[0, 0], (1, 0, 0, 128 / 255))
    rgb = fit_channels(read_image(tmp_path / "c.png")[..., :3], "color", single=False)
    assert np.allclose(rgb[..., 3], 1.0)  # no alpha: the colour replaces the blades' fully
    assert fit_channels(colour, "density", single=True).shape == (8, 8, 1)


def test_raw_sixteen_bit_with_byte_order_and_range(tmp_path):
    values = np.array([[0, 65535], [32768, 1000]], np.uint16)
    (tmp_path / "h.r16").write_bytes(values.astype(">u2").tobytes())
    h = read_raw16(tmp_path / "h.r16", 2, 2, big_endian=True, low=0.2, high=0.6)
    assert h[0, 0, 0] == pytest.approx(0.2) and h[0, 1, 0] == pytest.approx(0.6)
    wrong = read_raw16(tmp_path / "h.r16", 2, 2, big_endian=False)
    assert wrong[0, 1, 0] == pytest.approx(1.0) and wrong[1, 1, 0] != h[1, 1, 0]
    with pytest.raises(MapFileError, match=r"h.r16: 8 bytes, but 4 × 4 16-bit values need 32"):
        read_raw16(tmp_path / "h.r16", 4, 4)


def test_resampling_keeps_the_shape_of_the_map():
    ramp = np.linspace(0, 1, 128, dtype=np.float32)[None, :, None].repeat(64, axis=0)
    small = resample(ramp, (32, 16))
    assert small.shape == (16, 32, 1)
    assert np.all(np.diff(small[8, :, 0]) > 0) and abs(small.mean() - 0.5) < 0.01


@pytest.mark.parametrize(
    ("name", "content", "reason"),
    [
        ("notes.png", b"just some text", "not an image"),
        ("cut.png", None, "damaged or truncated"),
        ("cmyk.tif", "CMYK", "unusable image mode CMYK"),
    ],
)
def test_bad_files_are_refused_naming_file_and_reason(tmp_path, name, content, reason):
    path = tmp_path / name
    if content is None:
        Image.fromarray(np.zeros((64, 64), np.uint8)).save(tmp_path / "full.png")
        path.write_bytes((tmp_path / "full.png").read_bytes()[:60])
    elif isinstance(content, bytes):
        path.write_bytes(content)
    else:
        Image.new(content, (4, 4)).save(path)
    with pytest.raises(MapFileError, match=reason) as info:
        read_image(path)
    assert name in str(info.value)


def test_imports_are_bounded_and_only_known_formats_are_read(tmp_path):
    from PIL import Image

    from core.map_io import MAX_SIZE

    eps = tmp_path / "drawing.png"  # PostScript named .png: never handed to Ghostscript
    eps.write_bytes(b"%!PS-Adobe-3.0 EPSF-3.0\n%%BoundingBox: 0 0 10 10\nshowpage\n")
    with pytest.raises(MapFileError, match="not an image Sward reads"):
        read_image(eps)
    big = tmp_path / "big.png"  # a small file of very many pixels
    Image.new("1", (MAX_SIZE + 1, MAX_SIZE + 1)).save(big)
    assert big.stat().st_size < 10 << 20
    with pytest.raises(MapFileError, match="more than a map holds"):
        read_image(big)
    hot = tmp_path / "hot.tif"  # float values outside 0 … 1
    Image.fromarray(np.full((4, 4), 7.5, np.float32), "F").save(hot)
    with pytest.raises(MapFileError, match=r"0 … 1, found 7.5"):
        read_image(hot)
    fifo = tmp_path / "pipe.png"
    os.mkfifo(fifo)
    with pytest.raises(MapFileError, match="not a regular file"):
        read_image(fifo)
    with pytest.raises(MapFileError, match="not a regular file"):
        read_raw16(fifo, 4, 4)


@pytest.mark.parametrize(
    "low,high",
    [(float("nan"), 1.0), (0.0, float("nan")), (0.0, float("inf")), (-float("inf"), 1.0)],
)
def test_a_raw_height_range_that_is_no_finite_number_is_refused_naming_the_file(
    tmp_path, low, high
):
    path = tmp_path / "dem.r16"
    path.write_bytes(np.zeros(16, "<u2").tobytes())
    with pytest.raises(MapFileError, match=r"dem\.r16: the height range .* two finite numbers"):
        read_raw16(path, 4, 4, low=low, high=high)


@pytest.mark.parametrize("low,high", [(-3e38, 3e38), (1e308, -1e308)])
def test_a_raw_height_range_wider_than_float_heights_is_refused(tmp_path, low, high):
    path = tmp_path / "dem.r16"
    path.write_bytes(np.zeros(16, "<u2").tobytes())
    with pytest.raises(MapFileError, match=r"dem\.r16: the height range .* too wide"):
        read_raw16(path, 4, 4, low=low, high=high)


@pytest.mark.parametrize("mode", ["L", "I;16", "RGB", "RGBA", "P"])
def test_an_image_read_at_the_maps_size_equals_one_read_whole_and_resampled(tmp_path, mode):
    from core.map_io import read_image_at

    rng = np.random.default_rng(3)
    if mode == "I;16":
        image = Image.fromarray(rng.integers(0, 65535, (40, 60), dtype=np.uint16))
    elif mode == "P":
        image = Image.fromarray(rng.integers(0, 255, (40, 60, 3), dtype=np.uint8)).convert("P")
    else:
        shape = (40, 60) if mode == "L" else (40, 60, len(mode))
        image = Image.fromarray(rng.integers(0, 255, shape, dtype=np.uint8), mode)
    image.save(tmp_path / "m.png")
    whole = read_image(tmp_path / "m.png")
    small, own = read_image_at(tmp_path / "m.png", (25, 16))
    assert own == (60, 40) and small.shape == (16, 25, whole.shape[2])
    assert np.allclose(small, resample(whole, (25, 16)), atol=1e-6)


def test_an_8192_square_grey_image_imported_into_the_colour_map_stays_under_1_gb(tmp_path):
    """The import resamples each channel before it widens grey to float RGBA (it peaked at
    2.4 GB). Measured in a process of its own: its peak resident memory."""
    import subprocess
    import sys

    path = tmp_path / "big.png"
    ramp = np.linspace(0, 255, 8192, dtype=np.float32).astype(np.uint8)
    Image.fromarray(np.broadcast_to(ramp, (8192, 8192)).copy()).save(path, compress_level=1)
    code = (
        "import sys\n"
        "from core.map_io import fit_channels, read_image_at\n"
        "values, own = read_image_at(sys.argv[1], (256, 256))\n"
        "colour = fit_channels(values, 'color', single=False)\n"
        "assert own == (8192, 8192) and colour.shape == (256, 256, 4)\n"
        # VmHWM: this process's own peak (ru_maxrss would carry the forking parent's over exec)
        "print(next(l.split()[1] for l in open('/proc/self/status') if l.startswith('VmHWM')))\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code, str(path)], capture_output=True, text=True, timeout=300,
        cwd=os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert int(run.stdout) * 1024 < 2**30  # kilobytes
