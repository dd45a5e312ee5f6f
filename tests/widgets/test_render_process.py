"""The render processes behind the viewport: the window outlives them, and what they draw is
what `sward render` draws."""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from PIL import Image

from core.project_file import load_project, save_project
from tests.conftest import coverage
from tests.widgets.conftest import grab, wait_full

pytestmark = pytest.mark.gui


def test_a_render_process_killed_mid_frame_is_replaced_and_the_project_kept(
    window, qtbot, tmp_path
):
    vp = window.viewport
    window.panel.param("density").setValue(0.5)
    window.document.maps.write("color", 0, 0, np.full((40, 40, 4), 0.7, np.float32))
    before = grab(window)
    save_project(tmp_path / "before.sward", window.document)
    restarts = []
    vp.renderer_restarted.connect(restarts.append)
    full = vp.renderer.pids["full"]
    vp.camera.orbit(20.0, 0.0)  # a new full-quality frame starts ...
    vp.request_frame()
    qtbot.wait(150)
    os.kill(full, signal.SIGKILL)  # ... and its process dies in the middle of it
    qtbot.waitUntil(lambda: bool(restarts), timeout=20000)
    assert window.isVisible()
    assert "killed by signal 9" in restarts[0]
    assert "killed by signal 9" in window.statusBar().currentMessage()
    assert vp.renderer.pids["full"] != full
    vp.camera.orbit(-20.0, 0.0)
    vp.request_frame()
    after = grab(window)  # the next full-quality frame arrives, from the new process
    assert load_project(tmp_path / "before.sward").same_as(window.document)
    assert coverage(after) == pytest.approx(coverage(before), abs=0.02)
    assert np.abs(after.astype(int) - before.astype(int)).mean() < 2.0


def test_a_killed_draft_process_comes_back_too(window, qtbot):
    vp = window.viewport
    restarts = []
    vp.renderer_restarted.connect(restarts.append)
    os.kill(vp.renderer.pids["draft"], signal.SIGKILL)
    qtbot.waitUntil(lambda: bool(restarts), timeout=20000)
    # the new process is up (it said hello) and has drawn the state it was sent
    qtbot.waitUntil(lambda: vp.renderer.processes["draft"].max_image_size > 0, timeout=30000)
    qtbot.wait(2000)
    drafts = []
    vp.frame_rendered.connect(lambda stats: stats.draft and drafts.append(stats))
    vp.camera.orbit(15.0, 0.0)
    vp.request_frame()
    qtbot.waitUntil(lambda: bool(drafts), timeout=20000)
    wait_full(window)


def test_the_window_shows_what_sward_render_draws(window, qtbot, tmp_path):
    """The same project and camera: the window's full-quality frame and `sward render` agree
    pixel for pixel (one renderer, render/, in both)."""
    shown = grab(window)
    h, w = shown.shape[:2]
    project, out = tmp_path / "p.sward", tmp_path / "cli.png"
    save_project(project, window.document)
    command = [sys.executable, "-m", "app.cli", "render", "--project", str(project)]
    command += ["--camera", window.document.default_camera, "--size", f"{w}x{h}", "--out", str(out)]
    started = time.monotonic()
    subprocess.run(command, check=True, capture_output=True, timeout=300)
    assert time.monotonic() - started < 300
    with Image.open(out) as image:
        drawn = np.asarray(image.convert("RGB"))
    assert drawn.shape == shown.shape
    assert np.array_equal(drawn, shown)


def test_shared_files_lose_their_names_once_mapped(window, qtbot):
    """The frames and the map stack travel through files in /dev/shm: each is unlinked as soon
    as the render process has mapped it, so even a killed window leaves none behind."""
    grab(window)
    paths = [
        f.path
        for p in window.viewport.renderer.processes.values()
        for f in (p.out, p.stack)
        if f is not None
    ]
    assert len(paths) == 4  # a frame file and a stack copy per process
    qtbot.waitUntil(lambda: not any(os.path.exists(path) for path in paths), timeout=10000)


@pytest.mark.skipif(not hasattr(os, "SCHED_IDLE"), reason="Linux's idle scheduling")
def test_after_its_first_frame_the_full_process_yields_the_cores_to_drafts(window, qtbot):
    """Drafts answer input; a full frame drawn meanwhile, made stale by that input, must not
    take the cores they draw with (render/render_server.py _yield_to_others). Before its first
    frame the full process keeps nice 10, so the start is not held back."""
    vp = window.viewport
    wait_full(window)
    full = vp.renderer.pids["full"]

    def policies(pid: int) -> set[int]:
        return {os.sched_getscheduler(int(t)) for t in os.listdir(f"/proc/{pid}/task")}

    assert len(os.listdir(f"/proc/{full}/task")) > 1  # llvmpipe's threads among them
    qtbot.waitUntil(lambda: policies(full) == {os.SCHED_IDLE}, timeout=5000)
    assert os.SCHED_IDLE not in policies(vp.renderer.pids["draft"])


WINDOW_PROCESS = """
import sys, time
from PySide6.QtWidgets import QApplication
app = QApplication(sys.argv)
from app.designer import DesignerWindow
from app.scenes import get_scene
window = DesignerWindow(get_scene("patch-grid").document())
window.show()
start = time.monotonic()
while window.viewport.last_stats.draft or window.viewport.last_stats.t_a_ms <= 0.0:
    app.processEvents()
    time.sleep(0.01)
    if time.monotonic() - start > 120:
        sys.exit("no full frame")
gl = sorted(m for m in sys.modules if m.split(".")[0] in ("moderngl", "glcontext"))
window.close()
print("GL:", ",".join(gl))
"""


def test_the_window_process_shows_full_frames_without_importing_gl(tmp_path):
    """The designer's own process draws no GL: after its first full-quality frame is on
    screen, neither moderngl nor glcontext has been imported there (the render processes
    draw; DESIGN.md)."""
    env = {**os.environ, "QT_QPA_PLATFORM": "xcb", "SWARD_CACHE": str(tmp_path)}
    env["XDG_CONFIG_HOME"] = str(tmp_path)  # the window's settings of its own
    r = subprocess.run(
        [sys.executable, "-c", WINDOW_PROCESS], capture_output=True, text=True, env=env,
        timeout=240,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip().splitlines()[-1] == "GL:", r.stdout


def test_every_document_change_reaches_both_render_processes(window, qtbot):
    """Each kind of document field, changed in the window, is the same in the copy each render
    process draws from; and after a height stroke under a rock, the rock stands on the new
    ground in both."""
    import json

    from app.scenes import get_scene
    from core.project_file import document_data
    from tests.core.test_document import _every_field_kind

    window.open_document(get_scene("meadow").document())
    doc, vp = window.document, window.viewport

    def plain(data) -> str:
        return json.dumps(data, sort_keys=True)

    def check(what: str) -> None:
        for role in ("draft", "full"):
            facts = vp.renderer_facts(role=role)
            assert plain(facts["document"]) == plain(document_data(doc)), (what, role)
            assert np.array_equal(facts["prop_boxes"], doc.prop_boxes()), (what, role)

    for kind, change in _every_field_kind(doc):
        change()
        check(kind)
    # a stroke of height under the first rock, then the terrain rebuilt (as after a stroke)
    (x, z), scale = doc.props[0].position, doc.terrain_spec.height_scale
    column, row = (np.array([x, z]) / [doc.terrain_spec.columns, doc.terrain_spec.rows] + 0.5) * (
        doc.maps.size
    )
    before = doc.prop_boxes()["centre"][0, 1]
    doc.maps.write("height", int(column) - 8, int(row) - 8, np.ones((16, 16, 1), np.float32))
    doc.rebuild_terrain()
    assert doc.prop_boxes()["centre"][0, 1] > before + 0.5 * scale
    check("height stroke")
