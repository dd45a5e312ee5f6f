"""What the viewport's colours mean, drawn over the frame: the Compare view's column names,
the LOD zone rings' colours and the Quality view's heat scale (the rings' and the heat scale
share the bottom-right corner: the Quality view shows no rings' legend)."""

from __future__ import annotations

from dataclasses import dataclass

from PySide6.QtCore import QRect, QRectF, Qt
from PySide6.QtGui import QColor, QFontMetrics, QLinearGradient, QPainter, QPen

from core.view_mode import ViewMode

NAMES = {"geometry": "geometry", "volume": "volume", "image": "image-based"}
PAD = 6


@dataclass(frozen=True)
class Legend:
    kind: str  # column | zones | heat
    texts: tuple[str, ...]


def legends(mode: ViewMode, zones: bool, heat: bool) -> list[Legend]:
    """The legends a view shows: Compare names its three columns, the zone rings say which
    colour is which representation, the Quality view's heat map says what its colours count."""
    shown = []
    if mode == ViewMode.COMPARE:
        shown.append(Legend("column", tuple(NAMES.values())))
    if zones and not heat:
        names = tuple(f"{name} zone" for name in NAMES.values())
        shown.append(Legend("zones", ("rings: where a zone begins or ends", *names)))
    if heat:
        shown.append(Legend("heat", ("difference from all geometry (FLIP)", "0 same", "0.5", "1")))
    return shown


def paint(p: QPainter, rect: QRect, shown: list[Legend], zone_colors: dict) -> None:
    metrics = QFontMetrics(p.font())
    line = metrics.height()
    p.setRenderHint(QPainter.RenderHint.Antialiasing)
    bottom = rect.bottom()  # the corner boxes stand above Compare's column names
    if any(legend.kind == "column" for legend in shown):
        bottom -= line + 3 * PAD
    for legend in shown:
        if legend.kind == "column":
            for k, text in enumerate(legend.texts):
                left = rect.left() + rect.width() * k // 3
                right = rect.left() + rect.width() * (k + 1) // 3
                w = metrics.horizontalAdvance(text) + 2 * PAD
                # at the bottom: the timings overlay holds the top-left corner
                box = QRect((left + right - w) // 2, rect.bottom() - line - 2 * PAD, w, line + PAD)
                _box(p, box)
                p.drawText(box, Qt.AlignmentFlag.AlignCenter, text)
        elif legend.kind == "zones":
            title, *names = legend.texts
            w = max(
                metrics.horizontalAdvance(title), 36 + max(map(metrics.horizontalAdvance, names))
            )
            h = line * len(legend.texts) + 2 * PAD
            box = QRect(rect.right() - w - 3 * PAD, bottom - h - PAD, w + 2 * PAD, h)
            _box(p, box)
            p.drawText(box.adjusted(PAD, PAD, 0, 0), title)
            for k, (rep, text) in enumerate(zip(NAMES, names, strict=True)):
                y = box.top() + PAD + line * (k + 1) + line // 2
                r, g, b, _a = zone_colors[rep]
                p.setPen(QPen(QColor.fromRgbF(r, g, b), 3))
                p.drawLine(box.left() + PAD, y, box.left() + PAD + 28, y)
                p.setPen(QColor(255, 255, 255))
                p.drawText(box.left() + PAD + 36, y + metrics.ascent() // 2 - 1, text)
        elif legend.kind == "heat":
            title, *ticks = legend.texts
            w, h = 220, line * 3 + 2 * PAD
            box = QRect(rect.right() - w - PAD, bottom - h - PAD, w, h)
            _box(p, box)
            p.drawText(box.adjusted(PAD, PAD, -PAD, 0), Qt.AlignmentFlag.AlignHCenter, title)
            bar = QRectF(box.left() + PAD, box.top() + PAD + line, w - 2 * PAD, line * 0.8)
            ramp = QLinearGradient(bar.topLeft(), bar.topRight())
            # core/quality.py heat_map: black through red and yellow to white
            for stop, colour in ((0, "black"), (1 / 3, "red"), (2 / 3, "yellow"), (1, "white")):
                ramp.setColorAt(stop, QColor(colour))
            p.fillRect(bar, ramp)
            for text, at in zip(ticks, (0.0, 0.5, 1.0), strict=True):
                x = bar.left() + bar.width() * at
                tw = metrics.horizontalAdvance(text)
                x = min(max(x - tw / 2, box.left() + PAD), box.right() - PAD - tw)
                p.drawText(int(x), int(bar.bottom() + line - 2), text)


def _box(p: QPainter, box: QRect) -> None:
    p.fillRect(box, QColor(0, 0, 0, 160))
    p.setPen(QColor(255, 255, 255))
