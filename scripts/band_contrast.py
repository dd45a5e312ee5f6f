"""Fine contrast by bands of rows: the mean over 4 × 4-pixel blocks of the luminance's standard
deviation (× 1000), per band, for each image given. Compares how much blade detail frames show,
e.g. the heat-map run's all-geometry and LOD frames with the wind on and off:

    sward quality --scene meadow --camera path --wind off --out still
    sward quality --scene meadow --camera path --wind on --time 2 --out wind
    .venv/bin/python scripts/band_contrast.py still/path-geometry.png still/path-lod.png \
        wind/path-geometry.png wind/path-lod.png [--bands 100:116,116:132,132:150]
"""

from __future__ import annotations

import argparse

import numpy as np
from PIL import Image

BLOCK = 4


def band_contrast(path: str, bands: list[tuple[int, int]]) -> list[float]:
    rgb = np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0
    lum = rgb @ np.array([0.2126, 0.7152, 0.0722])
    out = []
    for top, bottom in bands:
        part = lum[top:bottom]
        h, w = (part.shape[0] // BLOCK) * BLOCK, (part.shape[1] // BLOCK) * BLOCK
        blocks = part[:h, :w].reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK)
        out.append(float(blocks.std(axis=(1, 3)).mean()) * 1000.0)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("images", nargs="+")
    ap.add_argument("--bands", default="100:116,116:132,132:150,150:180,180:220,220:270")
    args = ap.parse_args()
    try:
        bands = [(int(a), int(b)) for a, b in (s.split(":") for s in args.bands.split(","))]
    except ValueError:
        ap.error(f"--bands {args.bands!r}: give TOP:BOTTOM,TOP:BOTTOM,…")
    print("rows".ljust(40) + " ".join(f"{a}-{b}".rjust(8) for a, b in bands))
    for path in args.images:
        values = band_contrast(path, bands)
        print(path[-40:].ljust(40) + " ".join(f"{v:8.1f}" for v in values))


if __name__ == "__main__":
    main()
