"""The renderer's picture is kept by its speed-ups: each fixed camera of tests/render/references.py
is drawn and compared with its stored reference at quarter resolution (FLIP <= 0.02), and the
metric itself tells a kept picture from a changed one."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks import references


@pytest.mark.parametrize("case", references.CASES, ids=lambda c: c.name)
def test_frame_matches_its_stored_reference(ctx, case):
    image = references.render(case, ctx)
    moved = references.moved(case, image)
    assert moved <= references.LIMIT, f"{case.name}: quarter-resolution FLIP {moved:.4f}"


def test_metric_sees_a_changed_picture(ctx):
    """The check can fail: the same frame a little darker, or with its grass shifted by a few
    pixels, moves further than the limit; the frame itself does not move at all."""
    case = references.by_name("meadow-path-lod-480x360")
    image = references.render(case, ctx)
    assert references.moved(case, image) < 0.2 * references.LIMIT
    darker = (image.astype(np.float32) * 0.85).astype(np.uint8)
    assert references.moved(case, darker) > references.LIMIT
    shifted = np.roll(image, 12, axis=1)
    assert references.moved(case, shifted) > references.LIMIT
