"""What leaves the window as files: the view as a PNG (File → Save image…) and the Timings
dock's recorded frames as CSV or JSON."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QApplication, QInputDialog, QMessageBox


def save_image_dialog(w) -> None:
    """Ask for a size (the window's, 2× or 4×) and a file, then save the view."""
    width, height = w.viewport.width(), w.viewport.height()
    sizes = {
        f"window size ({width} × {height})": 1,
        f"2 × ({2 * width} × {2 * height})": 2,
        f"4 × ({4 * width} × {4 * height})": 4,
    }
    choice, ok = QInputDialog.getItem(w, "Save image", "Size", list(sizes), 0, False)
    if not ok:
        return
    path = w.dialogs.save_path("Save image", "grass.png", "PNG (*.png)")
    if path:
        save_image(w, path, sizes[choice])


def save_image(w, path: str, scale: int = 1) -> bool:
    """Save the view as PNG at the viewport's size times `scale` (drawn anew, not
    enlarged)."""
    from PIL import Image

    size = (w.viewport.width() * scale, w.viewport.height() * scale)
    limit = w.viewport.image_size_limit()
    if max(size) > limit:
        QMessageBox.warning(
            w, "Sward", f"{size[0]} × {size[1]} is larger than this GPU draws ({limit})"
        )
        return False
    QApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
    try:
        image = w.viewport.render_image(size)
        Image.fromarray(image).save(path, format="PNG")
    except OSError as exc:
        QMessageBox.warning(w, "Sward", f"cannot write {path}: {exc.strerror or exc}")
        return False
    finally:
        QApplication.restoreOverrideCursor()
    w.statusBar().showMessage(f"saved {size[0]} × {size[1]} image to {path}", 5000)
    return True


def save_recording(w, frames: list) -> None:
    """The Timings dock's recorded frames to a CSV or JSON file the person picks."""
    if not frames:
        w.statusBar().showMessage("nothing recorded: no frame was drawn", 5000)
        return
    path = w.dialogs.save_path("Save recorded frames", "timings.csv", "CSV (*.csv);;JSON (*.json)")
    if not path:
        return
    try:
        text = w.profile_panel.save(path, frames, scene=w.document.name)
    except OSError as exc:
        QMessageBox.warning(w, "Sward", f"cannot write {path}: {exc.strerror or exc}")
        return
    w.statusBar().showMessage(text, 5000)
