"""The verdict section: one paragraph worded from the numbers, a bar chart of what the
polysegment wins and loses against each polyline variant (in %), and the gates in one line."""

from __future__ import annotations

from typing import Any, Mapping, Sequence

from coatsim.report.html import Figure, Section, esc, figure_html
from coatsim.report.plots import figure, grid, png_bytes, title
from coatsim.report.verdict import Verdict, advantage_pct, change_text, overall, verdict

CLIP_PCT = 100.0  # bars beyond ±100 % are drawn to the edge and labelled with their value
OUTCOME_COLOURS = {"win": "#2e8b57", "loss": "#c0392b", "tie": "#9e9e9e", "undefined": "#d0d0d0"}


def gates_line(gates: Sequence[Mapping[str, Any]]) -> str:
    """The gates in one line: how many passed, and which failed."""
    if not gates:
        return "This scenario defines no gates."
    failed = [g for g in gates if not g["passed"]]
    text = f"Gates: {len(gates) - len(failed)} of {len(gates)} passed"
    if failed:
        text += "; FAILED: " + "; ".join(f"{g['label']} (value {g['value']:.4g}, reference {g['reference']:.4g})"
                                         if isinstance(g["value"], (int, float)) and isinstance(g["reference"], (int, float))
                                         else g["label"] for g in failed)
    return text + "."


def paragraph(result: Verdict, gates: Sequence[Mapping[str, Any]]) -> str:
    """The verdict in words: the overall sentence, one sentence per polyline variant, the gates."""
    return " ".join([overall(result), *(c.headline for c in result.comparisons), gates_line(gates)])


def bar_chart(result: Verdict) -> bytes:
    """One panel per polyline variant: the polysegment's advantage per measure in %
    (right = better for the polysegment), coloured by outcome."""
    n = len(result.comparisons)
    fig = figure(3.9 * n + 1.6, 2.5)
    axes = grid(fig, 1, n, margins=(1.45, 0.15, 0.3, 0.5), gaps=(0.3, 0.0), sharey=True)[0]
    for ax, c in zip(axes, result.comparisons):
        widths, colours, notes = [], [], []
        for o in c.outcomes:
            adv = advantage_pct(o)
            if adv is None:  # no ratio (the polyline's value is 0): a win or a loss runs to the edge
                widths.append({"win": CLIP_PCT, "loss": -CLIP_PCT}.get(o.outcome, 0.0))
            else:
                widths.append(max(-CLIP_PCT, min(CLIP_PCT, adv)))
            colours.append(OUTCOME_COLOURS[o.outcome])
            word = {"win": "win", "loss": "loss", "tie": "tie", "undefined": ""}[o.outcome]
            notes.append(f"{word} {change_text(o) if o.outcome != 'undefined' else 'n/a'}".strip())
        ax.barh(range(len(widths)), widths, color=colours, height=0.6)
        for y, (width, note) in enumerate(zip(widths, notes)):
            ax.text(width + (4 if width >= 0 else -4), y, note, va="center", ha="left" if width >= 0 else "right",
                    fontsize=7.5)
        ax.axvline(0.0, color="black", lw=0.8)
        ax.set_xlim(-CLIP_PCT * 1.9, CLIP_PCT * 1.9)
        ax.set_xticks([-100, -50, 0, 50, 100])
        ax.set_yticks(range(len(c.outcomes)), [o.criterion.label for o in c.outcomes])
        title(ax, f"against {c.against}")
        ax.set_xlabel("polysegment better → (%)", fontsize=8)
        ax.grid(axis="x", alpha=0.3)
    axes[0].invert_yaxis()  # shared: the first measure on top in every panel
    return png_bytes(fig)


def section(data: Any) -> Section:
    document = data.document
    result = verdict(document)
    body = f'<p class="verdict">{esc(paragraph(result, document["gates"]))}</p>'
    if result.comparisons:
        body += figure_html(Figure(
            "What the polysegment wins and loses", bar_chart(result),
            "Per polyline variant and measure, the polysegment's change against it in %, drawn so that right is better "
            "for the polysegment (a shorter cycle time, a higher lowest speed, a lower CV). Green: a win, red: a loss, "
            f"grey: a tie (within 2 % or the metric's resolution). Bars beyond ±{CLIP_PCT:.0f} % stop at the edge; "
            "the label gives the value."))
    return Section("verdict", "Verdict", body)
