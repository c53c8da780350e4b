"""The verdict section: one paragraph worded from the numbers, a bar chart of what the
polysegment wins and loses against each polyline variant (in %), and the gates in one line."""

from __future__ import annotations

from typing import Any, Mapping, Sequence

from coatsim.report.html import Section, chart_html, esc
from coatsim.report.verdict import Comparison, Verdict, advantage_pct, change_text, overall, verdict

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


def bar_rows(c: Comparison) -> list[tuple[str, float, str, str]]:
    """Per measure of one comparison: its label, the bar's signed length in % of the polysegment's
    advantage (clipped at ±CLIP_PCT; a win or loss without a ratio runs to the edge), its outcome
    and the note beside it."""
    rows = []
    for o in c.outcomes:
        adv = advantage_pct(o)
        if adv is None:
            width = {"win": CLIP_PCT, "loss": -CLIP_PCT}.get(o.outcome, 0.0)
        else:
            width = max(-CLIP_PCT, min(CLIP_PCT, adv))
        note = "n/a" if o.outcome == "undefined" else f"{o.outcome} {change_text(o)}"
        rows.append((o.criterion.label, width, o.outcome, note))
    return rows


def bar_chart(result: Verdict) -> str:
    """One HTML bar chart per polyline variant: the polysegment's advantage per measure in %
    (right = better for the polysegment), coloured by outcome. Drawn by the browser from a few
    styled elements: crisp at any zoom, and nothing to rasterise."""
    panels = []
    for c in result.comparisons:
        rows = []
        for label, width, outcome, note in bar_rows(c):
            half = 50.0 * abs(width) / CLIP_PCT  # % of the track; the zero line is at its middle
            left = 50.0 if width >= 0 else 50.0 - half
            rows.append(f'<tr><th class="l">{esc(label)}</th><td class="track"><span style="left:{left:.2f}%;'
                        f'width:{half:.2f}%;background:{OUTCOME_COLOURS[outcome]}"></span></td>'
                        f'<td class="l">{esc(note)}</td></tr>')
        scale = ('<tr><td></td><td class="scale"><span>−100 %</span><span>0</span><span>+100 %</span></td>'
                 '<td class="l muted">polysegment better →</td></tr>')
        panels.append(f'<table class="bars"><caption>against {esc(c.against)}</caption>{"".join(rows)}{scale}</table>')
    return f'<div class="bar-charts">{"".join(panels)}</div>'


def section(data: Any) -> Section:
    document = data.document
    result = verdict(document)
    body = f'<p class="verdict">{esc(paragraph(result, document["gates"]))}</p>'
    if result.comparisons:
        body += chart_html(
            "What the polysegment wins and loses", bar_chart(result),
            "Per polyline variant and measure, the polysegment's change against it in %, drawn so that right is better "
            "for the polysegment (a shorter cycle time, a higher lowest speed, a lower CV). Green: a win, red: a loss, "
            f"grey: a tie (within 2 % or the metric's resolution). Bars beyond ±{CLIP_PCT:.0f} % stop at the edge; "
            "the label gives the value.")
    return Section("verdict", "Verdict", body)
