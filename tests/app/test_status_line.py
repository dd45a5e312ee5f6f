"""The designer's status line (app/status_line.py), without Qt."""

from app.status_line import quality_text, status_text
from core.stats import FrameStats


def test_a_draft_says_a_full_frame_follows_and_a_full_frame_gives_each_technique():
    draft = FrameStats(t_a_ms=61.4, blades=1200, triangles=9600, c_g=3, c_v=4, c_i=5, draft=True)
    full = FrameStats(
        t_a_ms=480.2, t_g_ms=45.0, t_v_ms=290.4, t_i_ms=80.0, t_m_ms=52.0, c_g=3, c_v=4, c_i=5
    )
    text = status_text(draft)
    assert "draft 61 ms, full quality follows" in text and "1,200 blades" in text
    assert "cells g/v/i 3/4/5" in text
    text = status_text(full, busy="converting slices of grass type 1", fly_speed=2.5)
    assert text.startswith("converting slices of grass type 1 · ")
    assert "frame 480 ms (g 45 · v 290 · i 80 · ground 52 ms)" in text
    assert text.endswith("F to leave)") and "fly mode, 2.5 units/s" in text
    # with the blades' shadows on, their pass is named too
    shaded = FrameStats(t_a_ms=811.0, t_g_ms=91.0, t_v_ms=307.0, t_i_ms=77.0, t_m_ms=250.0,
                        t_s_ms=40.0)  # fmt: skip
    assert "(g 91 · v 307 · i 77 · ground 250 · shadows 40 ms)" in status_text(shaded)


def test_while_drafts_carry_the_wind_no_full_frame_is_promised():
    draft = FrameStats(t_a_ms=61.4, draft=True)
    text = status_text(draft, wind_on_drafts=True)
    assert "full quality follows" not in text and "Sharp wind frames" in text


def test_the_quality_view_names_each_technique_it_measured():
    figures = {
        "lod": {"flip_quarter": 0.0412, "block_color": 0.0123},
        "techniques": {
            "geometry": {"flip_quarter": 0.02},
            "volume": {"flip_quarter": None},
            "image": {"flip_quarter": 0.05},
        },
        "lod_ms": 480.0,
        "geometry_ms": 9600.0,
        "speedup": 20.0,
    }
    text = quality_text(figures)
    assert "FLIP 0.041 (quarter resolution; geometry 0.020, image 0.050)" in text
    assert "volume" not in text and "(20.0x faster)" in text
    figures["techniques"] = {}
    assert "no grass" in quality_text(figures)
