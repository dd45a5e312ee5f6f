"""What the viewport's colours mean is drawn over the frame: Compare's column names and the
zone rings' colours (the Quality view's heat scale: test_designer's Quality view test)."""

import numpy as np
import pytest
from PySide6.QtCore import Qt

from tests.widgets.conftest import wait_full

pytestmark = pytest.mark.gui


def shown(vp) -> np.ndarray:
    """The viewport as a person sees it (the frame and what is painted over it)."""
    qimage = vp.grab().toImage()
    qimage = qimage.convertToFormat(qimage.Format.Format_RGB888)
    w, h = qimage.width(), qimage.height()
    data = np.frombuffer(qimage.constBits(), np.uint8, count=qimage.sizeInBytes())
    return data.reshape(h, qimage.bytesPerLine())[:, : w * 3].reshape(h, w, 3).astype(float)


def test_compare_names_its_columns_and_the_zone_rings_say_their_colours(window, qtbot):
    vp = window.viewport
    assert vp.legends() == []  # the plain view: nothing over the grass
    plain = shown(vp)
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    vp.setFocus()
    qtbot.keyClick(vp, Qt.Key.Key_5, Qt.KeyboardModifier.ControlModifier)
    wait_full(window)
    (columns,) = vp.legends()
    assert columns.texts == ("geometry", "volume", "image-based")
    image = shown(vp)
    h, w = image.shape[:2]
    frame = vp.frame_image().astype(float)
    for k in range(3):  # a label box under each column's middle, over the frame
        label = (slice(h - 24, h - 8), slice(w * (2 * k + 1) // 6 - 15, w * (2 * k + 1) // 6 + 15))
        assert np.abs(image[label] - frame[label]).mean() > 10, k
    qtbot.keyClick(vp, Qt.Key.Key_1, Qt.KeyboardModifier.ControlModifier)
    qtbot.keyClick(vp, Qt.Key.Key_Z)
    assert vp.show_zones
    wait_full(window)
    (zones,) = vp.legends()
    assert zones.kind == "zones" and zones.texts[1:] == (
        "geometry zone",
        "volume zone",
        "image-based zone",
    )
    corner = (slice(h - 50, h - 12), slice(w - 60, w - 12))
    assert np.abs(shown(vp)[corner] - plain[corner]).mean() > 10
