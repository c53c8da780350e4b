"""sweep.html: one self-contained page for a whole sweep.

Sections: ``summary`` (what ran), ``plots`` (each chosen metric against each axis, one colour per
variant; where other axes vary, one line style per combination of them), ``failed`` (every failed row
with its error), ``gates`` (points that failed a gate), ``table`` (the results table). Plots are
drawn with matplotlib's object API (no pyplot state), PNGs without a timestamp.
"""

from __future__ import annotations

import io
import json
from typing import Any, Mapping, Sequence

from coatsim.report.catalogue import METRICS
from coatsim.report.html import Figure, Section, esc, fmt, key_value_table, render_html
from coatsim.report.plots import VARIANT_COLOURS
from coatsim.sweep.table import Table, axis_column

_MAX_LINES = 8  # beyond this many combinations of the other axes, points are drawn unconnected


def _numeric(values: Sequence[Any]) -> bool:
    return all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values if v is not None)


def _key(value: Any) -> str:
    return json.dumps(value, sort_keys=True) if not isinstance(value, str) else value


def metric_figure(table: Table, axes: Sequence[str], variants: Sequence[str], metric: str) -> bytes:
    """PNG: ``metric`` against each axis (one panel each), one colour per variant; where other
    axes vary, one line style per combination of them (up to ``_MAX_LINES``, else unconnected)."""
    from matplotlib.figure import Figure as MplFigure

    rows = [dict(zip(table.columns, r)) for r in table.rows]
    axes = [axis_column(a) for a in axes]
    fig = MplFigure(figsize=(5.0 * min(len(axes), 3), 4.4 * ((len(axes) + 2) // 3)), dpi=90)
    panels = fig.subplots((len(axes) + 2) // 3, min(len(axes), 3), squeeze=False).ravel()
    styles = ("-", "--", ":", "-.")
    markers = ("o", "s", "^", "D", "v", "P", "X", "*")
    for ax, axis in zip(panels, axes):
        xs_all = [r[axis] for r in rows]
        numeric = _numeric(xs_all)
        order = list(dict.fromkeys(_key(x) for x in xs_all if x is not None))
        done = [r for r in rows if r["status"] == "ok" and r[metric] is not None and r[axis] is not None]
        # the other axes that vary among the finished rows tell the lines apart
        others = [a for a in axes if a != axis and len({_key(r[a]) for r in done}) > 1]
        combos = list(dict.fromkeys(", ".join(f"{a}={_key(r[a])}" for a in others) for r in done))
        connect = len(combos) <= _MAX_LINES
        for variant in variants:
            for c, combo in enumerate(combos):
                members = [r for r in done if r["variant"] == variant
                           and ", ".join(f"{a}={_key(r[a])}" for a in others) == combo]
                if not members:
                    continue
                pts = sorted((float(r[axis]) if numeric else order.index(_key(r[axis])), r[metric]) for r in members)
                label = variant + (f" ({combo})" if combo and connect else "")
                ax.plot([p[0] for p in pts], [p[1] for p in pts], color=VARIANT_COLOURS.get(variant, "#555555"),
                        ls=styles[c % len(styles)] if connect else "none", marker=markers[c % len(markers)], ms=4,
                        lw=1.2, label=label if connect or c == 0 else None)
        if not numeric:
            ax.set_xticks(range(len(order)), [o if len(o) <= 18 else o[:15] + "..." for o in order],
                          rotation=30, ha="right", fontsize=7)
        ax.set_xlabel(axis, fontsize=8)
        ax.set_ylabel(f"{metric} ({METRICS[metric].unit})", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
        if done:
            ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(0.0, -0.28 if numeric else -0.42), frameon=False)
        else:
            ax.text(0.5, 0.5, "no finished point", ha="center", va="center", transform=ax.transAxes, color="#999")
    for ax in panels[len(axes):]:
        ax.set_visible(False)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", metadata={"Software": None})
    return buf.getvalue()


def _table_html(table: Table) -> str:
    head = "".join(f"<th>{esc(c)}</th>" for c in table.columns)
    body = []
    for row in table.rows:
        cells = []
        for column, value in zip(table.columns, row):
            if column == "status":
                cells.append(f'<td class="l"><span class="{"pass" if value == "ok" else "fail"}">{esc(value)}</span></td>')
            elif isinstance(value, str):
                cells.append(f'<td class="l">{esc(value)}</td>')
            else:
                cells.append(f"<td>{fmt(value)}</td>")
        body.append(f"<tr>{''.join(cells)}</tr>")
    return (f'<div style="overflow-x:auto"><table><thead><tr>{head}</tr></thead>'
            f"<tbody>{''.join(body)}</tbody></table></div>")


def _failed_html(table: Table, labels: Mapping[str, str]) -> str:
    rows = [dict(zip(table.columns, r)) for r in table.rows if r[table.columns.index("status")] != "ok"]
    if not rows:
        return '<p class="pass">Every point ran, every variant.</p>'
    body = "".join(f'<tr><td class="l">{esc(r["point"])}</td><td class="l">{esc(labels[r["point"]])}</td>'
                   f'<td class="l">{esc(r["variant"])}</td><td class="l">{esc(r["error"])}</td></tr>' for r in rows)
    return ('<table><tr><th class="l">point</th><th class="l">parameters</th><th class="l">variant</th>'
            f'<th class="l">error</th></tr>{body}</table>')


def _gates_html(gate_failures: Mapping[str, Sequence[str]], labels: Mapping[str, str]) -> str:
    if not gate_failures:
        return '<p class="muted">No point that ran failed a gate.</p>'
    body = "".join(f'<tr><td class="l">{esc(p)}</td><td class="l">{esc(labels[p])}</td>'
                   f'<td class="l">{esc("; ".join(g))}</td></tr>' for p, g in gate_failures.items())
    return f'<table><tr><th class="l">point</th><th class="l">parameters</th><th class="l">failed gates</th></tr>{body}</table>'


def render_sweep_html(title: str, summary: Sequence[tuple[str, Any]], table: Table, axes: Sequence[str],
                      variants: Sequence[str], metrics: Sequence[str], labels: Mapping[str, str],
                      gate_failures: Mapping[str, Sequence[str]], pngs: Mapping[str, bytes] | None = None) -> str:
    """The whole page; ``pngs`` holds the metric figures already drawn (elsewhere), by metric."""
    drawn = dict(pngs or {})
    figures = tuple(Figure(f"{m} against every axis", drawn[m] if m in drawn else metric_figure(table, axes, variants, m),
                           f"{METRICS[m].meaning} ({METRICS[m].unit}), from the results table; failed rows are left "
                           "out; one panel per axis, one colour per variant.") for m in metrics)
    sections = [
        Section("summary", "Sweep", key_value_table(summary)),
        Section("plots", "Metrics against the axes", figures=figures),
        Section("failed", "Failed points", _failed_html(table, labels)),
        Section("gates", "Gates", _gates_html(gate_failures, labels)),
        Section("table", "Results table",
                '<p class="muted">The same rows as results.csv and results.parquet.</p>' + _table_html(table)),
    ]
    return render_html(title, "coatsim sweep", sections)
