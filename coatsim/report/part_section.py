"""The report's view of a part: every contour drawn, and one table row per contour."""

from __future__ import annotations

from typing import Any, Mapping, Sequence

from coatsim.report.html import esc, fmt

# per-contour columns: (group, metric, heading)
COLUMNS = (
    ("segmentation", "n_segments", "segments"),
    ("segmentation", "n_corners", "corners"),
    ("segmentation", "max_deviation_mm", "deviation mm"),
    ("segmentation", "curve_length_mm", "length mm"),
    ("motion", "cycle_time_s", "cycle s"),
    ("motion", "fraction_at_speed", "at speed"),
    ("motion", "stops", "stops"),
)


def contours_table(rows: Sequence[Mapping[str, Any]]) -> str:
    """One row per contour (the "contours" of metrics.json), the columns for each variant."""
    variants = list(rows[0]["variants"]) if rows else []
    head = ('<tr><th class="l">contour</th><th>sprayed</th><th class="l">closed</th><th class="l">starts at</th>'
            + "".join(f"<th>{esc(v)}: {esc(h)}</th>" for v in variants for _, _, h in COLUMNS) + "</tr>")
    body = "".join(
        f'<tr><td class="l">{r["contour"]}</td><td>{r["spray_order"]}</td><td class="l">{fmt(r["closed"])}</td>'
        f'<td class="l">{esc(r["source"])}</td>'
        + "".join(f"<td>{fmt(r['variants'][v][g][n])}</td>" for v in variants for g, n, _ in COLUMNS) + "</tr>"
        for r in rows
    )
    return f"<table>{head}{body}</table>"


def part_summary(contours: Sequence[Any]) -> str:
    """One line for the scenario summary: contours, closed ones, samples, total length."""
    closed = sum(bool(c.curve.closed) for c in contours)
    length = sum(c.curve.length for c in contours)
    pieces = sum(getattr(c, "n_pieces", 0) for c in contours)
    return f"{len(contours)} contours ({closed} closed) from {pieces} drawn pieces, {length:.1f} mm in all"
