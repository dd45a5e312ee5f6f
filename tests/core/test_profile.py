import numpy as np
import pytest

from core.paths import sample_path
from core.profile import parts_add_up, summarize, table
from core.stats import FrameStats


def frame(t_a, **parts):
    return FrameStats(t_a_ms=t_a, **{f"{k}_ms": v for k, v in parts.items()}, c_g=3)


def test_summary_gives_median_min_max_per_column():
    frames = [frame(10.0, t_g=6.0), frame(20.0, t_g=15.0), frame(40.0, t_g=30.0)]
    s = summarize(frames)
    assert s["t_a"] == {"median": 20.0, "min": 10.0, "max": 40.0}
    assert s["fps"]["max"] == pytest.approx(100.0)
    assert s["c_g"]["median"] == 3
    assert s["parts_over_t_a"]["min"] == pytest.approx(0.6)
    text = table([("high", s)])
    assert text.splitlines()[2].startswith("high") and "median" in text and "max" in text


def test_parts_must_add_up_to_the_whole():
    assert parts_add_up(frame(100.0, t_q=1.0, t_g=60.0, t_v=30.0, t_m=5.0))
    assert not parts_add_up(frame(100.0, t_g=50.0))  # half the frame unaccounted for
    assert not parts_add_up(frame(10.0, t_g=20.0))  # parts longer than the frame


def test_path_samples_are_even_along_the_keys():
    keys = [((0, 1, 0), (0, 0, 0)), ((10, 1, 0), (10, 0, 0)), ((10, 1, 10), (10, 0, 10))]
    samples = sample_path(keys, 5)
    eyes = np.array([e for e, _ in samples])
    assert np.allclose(eyes[0], (0, 1, 0)) and np.allclose(eyes[-1], (10, 1, 10))
    steps = np.linalg.norm(np.diff(eyes, axis=0), axis=1)
    assert np.allclose(steps, 5.0)
    targets = np.array([t for _, t in samples])
    assert np.allclose(targets[2], (10, 0, 0))
    with pytest.raises(ValueError, match="at least two"):
        sample_path(keys[:1], 3)


def test_the_live_overlay_averages_the_frames_it_holds():
    import json

    from core.profile import frames_csv, frames_json, overlay_text, rolling

    frames = [
        FrameStats(t_a_ms=t, t_g_ms=t / 2, c_g=c) for t, c in ((10.0, 3), (20.0, 5), (60.0, 7))
    ]
    stats = rolling(frames)
    assert stats["t_a"] == (30.0, 10.0, 60.0) and stats["c_g"] == (5.0, 3.0, 7.0)
    text = overlay_text(frames)
    row = next(line for line in text.splitlines() if line.startswith("t_g"))
    assert [float(v) for v in row.split()[1:4]] == [15.0, 5.0, 30.0]
    assert row.endswith("ms, geometry")  # each row says what it counts
    assert "last 3 frames" in text
    rows = frames_csv(frames).splitlines()
    assert len(rows) == 4 and rows[2].split(",")[1] == "20.0"
    doc = json.loads(frames_json(frames, scene="meadow"))
    assert doc["scene"] == "meadow" and [f["c_g"] for f in doc["frames"]] == [3, 5, 7]
