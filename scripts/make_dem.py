"""A stand-in for a real digital elevation model: a 16-bit greyscale PNG of ridged, eroded-looking
hills (ridged fractal Perlin noise: sharp crests, steep flanks, broad valleys), the kind of height
map terrain tools export. For checking Sward on terrain it did not make itself:

    .venv/bin/python scripts/make_dem.py dem.png [--size 512] [--seed 3]
    .venv/bin/sward new dem.sward --scene meadow --height-map dem.png --height-scale 6
    .venv/bin/sward quality --project dem.sward
"""

from __future__ import annotations

import argparse

import numpy as np
from PIL import Image

from core.heights import ridged_hills


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--seed", type=int, default=3)
    args = parser.parse_args()
    heights = np.rint(ridged_hills(args.size, args.seed) * 65535).astype(np.uint16)
    Image.fromarray(heights).save(args.out)  # 16-bit greyscale (mode I;16)
    print(f"wrote {args.out} ({args.size} × {args.size}, 16-bit)")


if __name__ == "__main__":
    main()
