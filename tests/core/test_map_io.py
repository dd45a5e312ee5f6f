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
