"""Self-contained HTML report: one file, images embedded as base64 PNG, inline CSS and inline
scripts (the 3-D viewer, opening a collapsed listing at a linked line), no external assets, so
it opens anywhere, offline, without coatsim installed.
"""

from __future__ import annotations

import base64
import html
import math
from dataclasses import dataclass
from typing import Any, Mapping, Sequence


CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:2em auto;max-width:1200px;
padding:0 1em;color:#222;line-height:1.45}
h1{margin-bottom:.2em}h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;margin:.6em 0;font-size:.92em}
th,td{border:1px solid #ccc;padding:.25em .6em;text-align:right}
th{background:#f3f3f3}td.l,th.l{text-align:left}
tr.group td{background:#fafafa;font-weight:600;text-align:left}
.pass{color:#0a7d28;font-weight:600}.fail{color:#b3121f;font-weight:600}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #eee}
figcaption{color:#555;font-size:.9em}.muted{color:#777}
p.verdict{font-size:1.05em;background:#f6f8fa;border-left:4px solid #1b6ca8;padding:.6em .9em}
table.events td{vertical-align:top}tr.warn td:nth-child(3){color:#b3121f;font-weight:600}
tr.note td{color:#555}
pre.listing{font-size:.8em;line-height:1.35;max-height:40em;overflow:auto;background:#fafafa;padding:.5em}
pre.listing i{color:#999;font-style:normal}pre.listing .hit{background:#ffe3b3;display:inline-block;width:100%}
pre.listing span:target{outline:2px solid #c0392b}pre.listing .tag{color:#b3121f;font-weight:600}
details{margin:.4em 0}summary{cursor:pointer}
.viewer canvas{border:1px solid #ddd;max-width:100%;touch-action:none;cursor:grab}
.viewer .controls label{margin-right:.8em}
.bar-charts{display:flex;flex-wrap:wrap;gap:0 2.5em}table.bars{font-size:.85em}
table.bars caption{font-weight:600;text-align:left}table.bars th,table.bars td{border:none;padding:.15em .4em;background:none}
table.bars td.track{position:relative;width:16em;background:linear-gradient(90deg,#eee 1px,transparent 1px) 0 0/25% 100%;
border-left:1px solid #eee;border-right:1px solid #eee}
table.bars td.track::after{content:"";position:absolute;left:50%;top:0;bottom:0;border-left:1px solid #222}
table.bars td.track span{position:absolute;top:.25em;bottom:.25em}
table.bars td.scale{position:relative;height:1.1em;color:#777;font-size:.9em}
table.bars td.scale span{position:absolute;top:0}table.bars td.scale span:nth-child(1){left:0}
table.bars td.scale span:nth-child(2){left:50%;transform:translateX(-50%)}table.bars td.scale span:nth-child(3){right:0}
"""

# First script of the page: records script errors on <html data-script-errors> (read by tests).
ERROR_HOOK = ("window.addEventListener('error',function(e){var h=document.documentElement;"
              "h.setAttribute('data-script-errors',(h.getAttribute('data-script-errors')||'')+e.message+';')});")
# Last script: a link to a line of a collapsed listing opens the listing.
OPEN_TARGET = ("function coatsimOpen(){var t=location.hash&&document.getElementById(location.hash.slice(1));"
               "for(var e=t;e;e=e.parentElement){if(e.tagName==='DETAILS'){e.open=true;}}if(t){t.scrollIntoView();}}"
               "window.addEventListener('hashchange',coatsimOpen);coatsimOpen();")


@dataclass(frozen=True)
class Figure:
    """One embedded image: PNG bytes and a caption."""

    title: str
    png: bytes
    caption: str


@dataclass(frozen=True)
class Section:
    """A report section: an anchor id, a heading, HTML body (already escaped) and figures."""

    anchor: str
    heading: str
    body: str = ""
    figures: tuple[Figure, ...] = ()


def esc(value: Any) -> str:
    return html.escape(str(value), quote=True)


def fmt(value: Any) -> str:
    """A metric value as text: integers plainly, floats to 4 significant digits."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "–"
        return f"{value:.4g}"
    return esc(value)


def figure_html(fig: Figure) -> str:
    data = base64.b64encode(fig.png).decode("ascii")
    return (
        f'<figure><img alt="{esc(fig.title)}" src="data:image/png;base64,{data}">'
        f"<figcaption><b>{esc(fig.title)}.</b> {esc(fig.caption)}</figcaption></figure>"
    )


def chart_html(title: str, body: str, caption: str) -> str:
    """A figure drawn in HTML (``body``, already escaped) with its caption, as figure_html's."""
    return f"<figure>{body}<figcaption><b>{esc(title)}.</b> {esc(caption)}</figcaption></figure>"


def key_value_table(rows: Sequence[tuple[str, Any]]) -> str:
    """Two-column table of labels and values."""
    body = "".join(f'<tr><th class="l">{esc(k)}</th><td class="l">{esc(v)}</td></tr>' for k, v in rows)
    return f"<table>{body}</table>"


def gates_table(gates: Sequence[Mapping[str, Any]]) -> str:
    """One row per gate: the check, the measured value, the reference, pass or fail."""
    if not gates:
        return '<p class="muted">This scenario defines no gates.</p>'
    rows = []
    for g in gates:
        status = '<span class="pass">pass</span>' if g["passed"] else '<span class="fail">FAIL</span>'
        rows.append(
            f'<tr><td class="l">{esc(g["label"])}</td><td>{fmt(g["value"])}</td>'
            f'<td>{fmt(g["reference"])}</td><td class="l">{status}</td></tr>'
        )
    head = '<tr><th class="l">gate</th><th>value</th><th>reference</th><th class="l">result</th></tr>'
    return f"<table>{head}{''.join(rows)}</table>"


def render_html(title: str, subtitle: str, sections: Sequence[Section]) -> str:
    """The whole document: title, table of contents, sections in order."""
    toc = "".join(f'<li><a href="#{esc(s.anchor)}">{esc(s.heading)}</a></li>' for s in sections)
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{esc(title)}</title><style>{CSS}</style><script>{ERROR_HOOK}</script></head><body>",
        f"<h1>{esc(title)}</h1><p class=\"muted\">{esc(subtitle)}</p>",
        f"<nav><ol>{toc}</ol></nav>",
    ]
    for s in sections:
        parts.append(f'<section id="{esc(s.anchor)}"><h2>{esc(s.heading)}</h2>{s.body}')
        parts.extend(figure_html(f) for f in s.figures)
        parts.append("</section>")
    parts.append(f"<script>{OPEN_TARGET}</script></body></html>\n")
    return "\n".join(parts)
