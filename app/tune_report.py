"""What `sward tune` prints and draws: the report and the front plot (PNG)."""

from __future__ import annotations

from pathlib import Path

from core.tuning import Knobs


def _figures(c: dict) -> str:
    regions = ", ".join(f"{n} {v:.4f}" for n, v in c["regions"].items())
    pops = f", popping {c['popping']:.2f}" if c.get("popping") is not None else ""
    return f"{c['cost_ms']:.0f} ms, FLIP {c['flip_quarter']:.4f} ({regions}){pops}"


def report(result: dict) -> str:
    w, h = result["size"]
    target = (
        f"budget {result['budget_ms']:.0f} ms"
        if result["budget_ms"] is not None
        else f"quality FLIP ≤ {result['quality']:g}"
    )
    cands = result["candidates"]
    lines = [
        f"{result['scene']} at {w}x{h}, {', '.join(result['views'])}: {target}; "
        f"{len(cands)} settings tried ({result.get('stopped', '')}), "
        f"references {result['references_drawn']} drawn, {result['references_reused']} reused "
        f"({result.get('references_s', 0):.0f} s)",
        f"  shipped: {_figures(result['shipped'])}",
    ]
    model = result.get("cost_model")
    if model is not None:
        lines.append(
            f"  drawn by {result['workers']}; costs predicted from counts by a model of "
            f"{model['points']} settings measured here ({model['leave_one_out_error']:.1%} off "
            "on each left out of its fit)"
        )
    if result["chosen"] is None:
        lines.append("  nothing tried meets the target")
    else:
        c = cands[result["chosen"]]
        lines.append(f"  chosen:  {_figures(c)}  [{Knobs(**c['knobs']).label()}]")
    for v in result.get("verified", []):
        c = cands[v["candidate"]]
        lines.append(
            f"  measured in turns ({v['rounds']} rounds): {Knobs(**c['knobs']).label()} "
            f"{v['ms']:.0f} ms against shipped {v['shipped_ms']:.0f} ms, allowed "
            f"{v['allowed_ms']:.0f} ms: {'holds' if v['holds'] else 'over'}"
            + (f" (predicted {v['search_ms']:.0f} ms)" if v.get("predicted") else "")
        )
    better = result.get("better_than_shipped")
    if better is not None:
        lines.append(
            f"  as good as shipped in the frame and every region, at no more cost: "
            f"{_figures(cands[better])}  [{Knobs(**cands[better]['knobs']).label()}]"
        )
    if result.get("verdict"):
        lines.append(f"  {result['verdict']}")
    lines.append(f"  front: {len(result['front'])} settings; {result['elapsed_s']:.0f} s")
    return "\n".join(lines)


def plot_front(result: dict, path: Path) -> None:
    """Cost against FLIP, every candidate grey, the front joined, the shipped setting red and
    the chosen one green; the budget as a dashed line. Drawn with Pillow: the headless
    commands import no Qt, so no pyqtgraph here."""
    from PIL import Image, ImageDraw, ImageFont

    font = ImageFont.load_default(size=13)
    every = result["candidates"]
    w, h, m = 640, 420, 60
    # up to 3 × the budget (or the shipped cost): the settings far dearer would squeeze the
    # part that matters into a corner; how many are left out is written on the plot
    near = 3.0 * (result["budget_ms"] or every[0]["cost_ms"])
    shown = {i for i, c in enumerate(every) if c["cost_ms"] <= near or i == result["chosen"]}
    cands = {i: every[i] for i in shown}
    xs = [c["cost_ms"] for c in cands.values()]
    ys = [c["flip_quarter"] for c in cands.values()]
    x0, x1 = min(xs) * 0.95, max(xs) * 1.05
    y0, y1 = min(ys) * 0.95, max(ys) * 1.05
    if result["budget_ms"] is not None:
        x0, x1 = min(x0, result["budget_ms"] * 0.95), max(x1, result["budget_ms"] * 1.05)

    def at(x: float, y: float) -> tuple[float, float]:
        return (
            m + (x - x0) / max(x1 - x0, 1e-9) * (w - 1.5 * m),
            h - m - (y - y0) / max(y1 - y0, 1e-9) * (h - 1.7 * m),
        )

    image = Image.new("RGB", (w, h), "white")
    d = ImageDraw.Draw(image)
    d.line([at(x0, y0), at(x1, y0)], fill="black")
    d.line([at(x0, y0), at(x0, y1)], fill="black")
    for k in range(5):
        x, y = x0 + (x1 - x0) * k / 4, y0 + (y1 - y0) * k / 4
        px, _ = at(x, y0)
        _, py = at(x0, y)
        d.text((px - 12, h - m + 6), f"{x:.0f}", fill="black", font=font)
        d.text((4, py - 6), f"{y:.3f}", fill="black", font=font)
    d.text((w / 2 - 60, h - 22), "frame cost (ms)", fill="black", font=font)
    d.text(
        (4, 8),
        "FLIP against all-geometry (quarter resolution; lower is better)",
        fill="black",
        font=font,
    )
    if result["budget_ms"] is not None:
        bx, _ = at(result["budget_ms"], y0)
        for y in range(int(at(x0, y1)[1]), int(at(x0, y0)[1]), 8):
            d.line([(bx, y), (bx, y + 4)], fill=(120, 120, 120))
        d.text((bx + 4, at(x0, y1)[1]), "budget", fill=(90, 90, 90), font=font)
    if len(shown) < len(every):
        left = f"{len(every) - len(shown)} dearer settings beyond {near:.0f} ms not shown"
        d.text((w - 330, 28), left, fill=(90, 90, 90), font=font)
    for c in cands.values():
        px, py = at(c["cost_ms"], c["flip_quarter"])
        d.ellipse([px - 3, py - 3, px + 3, py + 3], fill=(170, 170, 170))
    front = [i for i in result["front"] if i in shown]
    line = [at(cands[i]["cost_ms"], cands[i]["flip_quarter"]) for i in front]
    if len(line) > 1:
        d.line(line, fill=(40, 90, 200), width=2)
    for i in front:
        px, py = at(cands[i]["cost_ms"], cands[i]["flip_quarter"])
        d.ellipse([px - 4, py - 4, px + 4, py + 4], fill=(40, 90, 200))
    marks = [(0, (220, 40, 30), "shipped")]
    if result["chosen"] is not None and result["chosen"] != 0:
        again = [v for v in result.get("verified", []) if v["candidate"] == result["chosen"]]
        label = "chosen"
        if again:  # where the search's time and the one measured in turns differ
            label += f" ({again[0]['ms']:.0f} ms in turns, shipped {again[0]['shipped_ms']:.0f})"
        marks.append((result["chosen"], (20, 160, 60), label))
    for i, colour, label in marks:
        px, py = at(cands[i]["cost_ms"], cands[i]["flip_quarter"])
        d.ellipse([px - 7, py - 7, px + 7, py + 7], outline=colour, width=3)
        d.text((px + 9, py - 14), label, fill=colour, font=font)
    image.save(path, format="PNG")
