"""Report figures and the self-contained HTML document."""

from __future__ import annotations

import base64
import re


from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.report import curve_figures, plots
from coatsim.report.catalogue import METRICS, names
from coatsim.report.html import Figure, Section, gates_table, render_html
from coatsim.report.metric_names import SHOWN, ratio_text, value_text
from coatsim.report.sections.tables import metrics_table

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _sample_poly() -> Polysegment:
    return Polysegment(chain((0.0, 0.0), 0.0, [0.0, 0.05, 0.0], [30.0, 20.0, 30.0]))


def test_figures_are_png_and_deterministic() -> None:
    poly = _sample_poly()
    xy, _ = poly.sample(0.5)
    first = curve_figures.part_figure([poly, poly], [xy, xy + 40.0], order=[1, 0])
    assert first.startswith(PNG_MAGIC)
    assert curve_figures.part_figure([poly, poly], [xy, xy + 40.0], order=[1, 0]) == first


def test_axes_and_colour_bars_carry_few_ticks() -> None:
    """Every tick is two lines and two labels to make and draw: the report's axes and colour bars
    show at most about plots.TICKS of them, whatever the data's range."""
    import numpy as np

    fig = plots.figure(6.0, 3.0)
    ax, bar_ax = plots.grid(fig, 1, 2)[0]
    ax.plot([-3.7, 1234.5], [0.001, 987.0])
    image = bar_ax.imshow(np.linspace(-17.0, 4321.0, 100).reshape(10, 10))
    bar = fig.colorbar(image, ax=bar_ax, ticks=plots.bar_ticks())
    plots.png_bytes(fig)
    for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim()), (bar.ax.yaxis, bar.ax.get_ylim())):
        shown = [t for t in axis.get_majorticklocs() if lo <= t <= hi]
        assert 2 <= len(shown) <= plots.TICKS + 1


def _variants() -> dict:
    return {
        v: {g: {n: (i + 1) * 0.5 for n in names(g)} for g in ("segmentation", "motion", "coating")}
        for i, v in enumerate(("polysegment", "polyline-stop"))
    }


def test_metrics_table_lists_every_metric_by_name_with_meaningful_ratios() -> None:
    html = metrics_table(_variants(), "polysegment")
    assert set(SHOWN) == set(METRICS)
    for key in METRICS:
        assert f">{SHOWN[key].label}<" in html.replace("&gt;", ">").replace("&lt;", "<")
    assert "polyline-stop / polysegment" in html
    assert html.count("<td>2</td>") == sum(s.ratio for s in SHOWN.values())  # 1.0 / 0.5 where a ratio means something


def test_fractions_show_in_percent_and_ratios_only_where_meaningful() -> None:
    assert value_text("motion.fraction_at_speed", 0.9805) == "98.05"
    assert value_text("motion.stops", 3) == "3" and value_text("coating.thickness_cv", None) == "–"
    assert ratio_text("segmentation.max_tangent_break_deg", 5.7, 1e-14) is None
    assert ratio_text("motion.cycle_time_s", 3.0, 2.0) == "1.5"
    assert ratio_text("motion.cycle_time_s", 3.0, 0.0) is None and ratio_text("motion.cycle_time_s", None, 2.0) is None


def test_gates_table_marks_failures() -> None:
    rows = [{"label": "a < 1", "value": 0.5, "reference": 1.0, "passed": True},
            {"label": "b <= 2", "value": 3.0, "reference": 2.0, "passed": False}]
    html = gates_table(rows)
    assert html.count('class="pass"') == 1 and html.count('class="fail"') == 1


def test_document_is_self_contained_and_escaped() -> None:
    poly = _sample_poly()
    png = curve_figures.part_figure([poly], [poly.sample(1.0)[0]])
    doc = render_html("job <1>", "sub & title", [
        Section("one", "First", "<p>x</p>", (Figure("curve", png, "a <b> caption"),)),
        Section("two", "Second", "<p>y</p>"),
    ])
    assert "job &lt;1&gt;" in doc and "a &lt;b&gt; caption" in doc
    assert '<a href="#one">First</a>' in doc and 'id="two"' in doc
    scripts = re.findall(r"<script([^>]*)>", doc)
    assert scripts and all("src" not in attrs for attrs in scripts)  # inline only
    sources = re.findall(r'src="([^"]+)"', doc)
    assert len(sources) == 1 and sources[0].startswith("data:image/png;base64,")
    assert base64.b64decode(sources[0].split(",", 1)[1]) == png
    assert not re.search(r'(href|src)="(https?:)?//', doc)



def test_ticks_drawn_as_plain_artists_keep_every_label_on_its_side() -> None:
    """coatsim.report.ticks replaces matplotlib's tick machinery: the labels the axes would show
    stay, the axis's on the left and below, a colour bar's on its right."""
    import numpy as np

    fig = plots.figure(6.0, 3.0)
    ax, bar_ax = plots.grid(fig, 1, 2)[0]
    ax.plot([0.0, 10.0], [0.0, 5.0])
    ax.set_xlabel("x (mm)")
    bar = fig.colorbar(bar_ax.imshow(np.linspace(0.0, 40.0, 100).reshape(10, 10)), ax=bar_ax, ticks=plots.bar_ticks())
    plots.png_bytes(fig)

    def shown(axes) -> list[tuple[float, str]]:
        """(x in display pixels, text) of every tick label drawn on ``axes``."""
        return [(float(x), text) for a in axes.get_children() if hasattr(a, "texts")
                for (x, _), text in zip(a.get_transform().transform(a.xy), a.texts)]

    assert not ax.xaxis.get_visible() and not bar.ax.yaxis.get_visible()  # drawn by the plain artists instead
    expected = []
    for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        locs = [t for t in axis.get_majorticklocs() if lo <= t <= hi]
        expected += axis.get_major_formatter().format_ticks(locs)
    assert sorted(text for _, text in shown(ax)) == sorted(expected) and len(expected) >= 4
    right = bar.ax.get_window_extent().x1
    assert len(shown(bar.ax)) >= 2 and all(x > right for x, _ in shown(bar.ax))
    assert "x (mm)" in [t.get_text() for t in ax.texts]


def test_nothing_drawn_on_a_part_reports_figures_is_cut_off_at_their_edges(tube_run) -> None:
    """Every figure of a 3-D part's report keeps its drawing inside its margins: the outermost row
    and column of pixels on each side are the background (a legend or label placed past the
    figure's edge, as the histogram's legend once was, is cut off there)."""
    import io

    import numpy as np
    from PIL import Image

    result, _ = tube_run
    html = (result.outdir / "report.html").read_text(encoding="utf-8")
    images = re.findall(r"data:image/png;base64,([A-Za-z0-9+/=]+)", html)
    assert images
    for k, data in enumerate(images):
        rgb = np.asarray(Image.open(io.BytesIO(base64.b64decode(data))).convert("RGB")).astype(int)
        edges = {"left": rgb[:, 0], "right": rgb[:, -1], "top": rgb[0], "bottom": rgb[-1]}
        cut = [side for side, pixels in edges.items() if np.abs(pixels - rgb[0, 0]).max() > 0]
        assert not cut, f"figure {k}: something drawn reaches its {', '.join(cut)} edge"
