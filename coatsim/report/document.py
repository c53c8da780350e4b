"""report.html of a run: every section built from the run's values and its metrics document.

Sections: scenario summary with the verdict (what the polysegment wins and loses against each
polyline, :mod:`coatsim.report.verdict`) and the headline metrics, curve and polysegment, θ, speed
profiles, thickness maps, cross-section, warnings, all metrics with ratios, gates.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np

from coatsim import __version__
from coatsim.fileio import write_text
from coatsim.report.catalogue import METRICS
from coatsim.report.html import Figure, Section, esc, fmt, gates_table, key_value_table, metrics_table, render_html
from coatsim.report.summary import headline_rows
from coatsim.report.verdict import Verdict, change_text, verdict
from coatsim.geometry.plots import segmentation_figure_png
from coatsim.report.plots import SpeedProfile, polyline_figure, speed_figure
from coatsim.spray.outputs import Profile, default_section, heatmap_png, panel, profile_png, section_profile

SECTION_TITLES = {
    "summary": "Scenario",
    "curve": "Curve, polysegment and θ",
    "polyline": "Polyline program",
    "speed": "Tool speed",
    "thickness": "Coating thickness",
    "section": "Thickness cross-section",
    "warnings": "Warnings",
    "metrics": "All metrics",
    "gates": "Gates",
}


def headline_table(document: Mapping[str, Any]) -> str:
    names = list(document["variants"])
    head = '<tr><th class="l">metric</th><th class="l">unit</th>' + "".join(f"<th>{esc(v)}</th>" for v in names) + "</tr>"
    body = "".join(
        f'<tr><td class="l">{esc(key)}</td><td class="l">{esc(METRICS[key].unit)}</td>'
        + "".join(f"<td>{fmt(x)}</td>" for x in values) + "</tr>"
        for key, values in headline_rows(document)
    )
    return f"<table>{head}{body}</table>"


def verdict_html(result: Verdict) -> str:
    """Per polyline variant: the headline sentence, then the five metrics with both values, the
    change and the outcome."""
    if not result.comparisons:
        return '<p class="muted">No polysegment and polyline variants to compare in this run.</p>'
    out = []
    for c in result.comparisons:
        head = (f'<tr><th class="l">metric</th><th>{esc(c.against)}</th><th>polysegment</th>'
                f'<th>change</th><th class="l">polysegment</th></tr>')
        rows = "".join(
            f'<tr><td class="l" title="{esc(METRICS[o.criterion.key].meaning)}">{esc(o.criterion.label)}</td>'
            f"<td>{fmt(o.polyline)}</td><td>{fmt(o.polysegment)}</td>"
            f"<td>{esc(change_text(o))}</td>"
            f'<td class="l">{_OUTCOME_HTML[o.outcome]}</td></tr>'
            for o in c.outcomes
        )
        out.append(f"<h3>Polysegment against {esc(c.against)}</h3><p>{esc(c.headline)}</p><table>{head}{rows}</table>")
    return "".join(out)


_OUTCOME_HTML = {"win": '<span class="pass">wins</span>', "loss": '<span class="fail">loses</span>',
                 "tie": "ties", "undefined": '<span class="muted">undefined</span>'}


def _summary_rows(loaded, curve, runs: Sequence, document: Mapping[str, Any]) -> list[tuple[str, Any]]:
    spec = loaded.spec
    c = spec.curve
    source = f"built-in {c.builtin} {json.dumps(c.params, sort_keys=True)}" if c.builtin else f"file {c.file}"
    wp = spec.workpiece
    size = {"plate": lambda: f"plate {wp.size_mm[0]:g} x {wp.size_mm[1]:g} mm",
            "cylinder": lambda: f"cylinder R {wp.radius_mm:g} x L {wp.length_mm:g} mm, axis {wp.axis}",
            "mesh": lambda: f"mesh {wp.file}"}[wp.kind]()
    seg = document["variants"].get("polysegment", {}).get("segmentation")
    rows = [
        ("scenario file", loaded.path.name),
        ("description", spec.description or "–"),
        ("curve", f"{source}; scale {c.scale:g}, rotated {c.rotate_deg:g} deg; {'closed' if curve.closed else 'open'}, "
                  f"{len(curve.points)} points, {curve.length:.1f} mm"),
        ("segmentation", f"tolerance {spec.segmentation.tolerance_mm:g} mm, method {spec.segmentation.method}, "
                         f"corners above {spec.segmentation.corner_deg:g} deg"),
        ("workpiece", f"{size} at {wp.pose.position_mm} mm, O-A-T {wp.pose.oat_deg} deg"),
        ("robot", spec.robot.model),
        ("gun", f"{spec.gun.footprint}, Q {spec.gun.flow_mm3_s:g} mm³/s, stand-off {spec.gun.standoff_mm:g} mm, "
                f"target {spec.gun.target_thickness_um:g} µm"),
        ("motion", f"{spec.motion.speed_mm_s:g} mm/s, accuracy {spec.motion.accuracy_mm:g} mm, run-in "
                   f"{spec.motion.lead_in_mm:g} mm, run-out {spec.motion.lead_out_mm:g} mm"),
        ("variants", ", ".join(spec.variants)),
        ("mode", f"{document['mode']} (coating mesh {loaded.spec.fast.coating_spacing_mm if document['mode'] == 'fast' else spec.coating.spacing_mm:g} mm)"),
    ]
    if seg is not None:
        rows.insert(4, ("polysegment", f"{seg['n_lines']} lines + {seg['n_arcs']} arcs, deviation "
                                       f"{seg['max_deviation_mm']:.4g} mm"))
    return rows


def _speed_profiles(runs: Sequence, lead_in_mm: float, lead_out_mm: float) -> tuple[dict[str, SpeedProfile], tuple[float, float]]:
    """Speed against path length from the start of the run-in to the end of the run-out (the
    curve proper in between), whether or not the gun is open on the run-in and run-out."""
    profiles, span = {}, (0.0, 0.0)
    for r in runs:
        log, (a, b) = r.execution.log, r.execution.curve
        # the log's progress is monotonic up to servo jitter: take the rows between the first
        # one at the run-in start and the first one past the run-out end
        reach = np.maximum.accumulate(log.progress)
        i0 = int(np.searchsorted(reach, a - lead_in_mm, side="left"))
        i1 = int(np.searchsorted(reach, b + lead_out_mm - 1e-6, side="left"))
        rows = slice(min(i0, len(log.progress) - 1), min(i1, len(log.progress) - 1) + 1)
        profiles[r.name] = SpeedProfile(log.progress[rows] - (a - lead_in_mm), log.speed[rows])
        span = (lead_in_mm, lead_in_mm + (b - a))
    return profiles, span


def build_sections(loaded, curve, segmentation, runs: Sequence, document: Mapping[str, Any]) -> list[Section]:
    """Every section of the report, in order."""
    spec = loaded.spec
    polyline = next((r.program.curve for r in runs if r.name != "polysegment"), None)
    polyline_xy = None if polyline is None else np.array([s.start for s in polyline.segments] + [polyline.end])
    profiles, span = _speed_profiles(runs, spec.motion.lead_in_mm, spec.motion.lead_out_mm)
    surface = runs[0].coating.surface
    top = max(float(np.percentile(r.coating.thickness_um, 99.5)) for r in runs)
    line = default_section(surface)
    heat = heatmap_png([panel(surface, r.coating.thickness_um, r.name) for r in runs], 0.0, top, section=line)
    cuts = [Profile(r.name, *section_profile(surface.view, surface.faces, r.coating.thickness_um, *line)) for r in runs]
    where = f"({line[0][0]:g}, {line[0][1]:g}) -> ({line[1][0]:g}, {line[1][1]:g}) mm"
    baseline = "polysegment" if "polysegment" in document["variants"] else None
    return [
        Section("summary", SECTION_TITLES["summary"], key_value_table(_summary_rows(loaded, curve, runs, document))
                + verdict_html(verdict(document))
                + "<h3>Every variant, headline metrics</h3>" + headline_table(document)),
        Section("curve", SECTION_TITLES["curve"], figures=(Figure(
            "Input curve, polysegment and θ", segmentation_figure_png(segmentation),
            "Left: the polysegment over the input curve, arcs and lines in their own colours, junctions as dots, "
            "true corners as crosses. Right: the angular function θ(t) (cumulative turning angle against "
            "normalised arc length) of the input and of the polysegment, piecewise linear: each slope is an arc, "
            "each flat piece a line."),)),
        *([] if polyline_xy is None else [Section("polyline", SECTION_TITLES["polyline"], figures=(Figure(
            "Polyline program", polyline_figure(curve.points, polyline_xy),
            "The polyline variants' vertices on the input curve: without blending the arm stops at each."),))]),
        Section("speed", SECTION_TITLES["speed"], figures=(Figure(
            "Tool speed against path length, every variant", speed_figure(profiles, spec.motion.speed_mm_s, span),
            "Simulated tool-centre-point speed along the run-in, the curve proper and the run-out, from the "
            "trajectory logs; the shaded ends are the run-in and run-out (on a closed contour the gun is closed "
            "there: it sprays exactly one lap, from the seam to the seam)."),)),
        Section("thickness", SECTION_TITLES["thickness"], figures=(Figure(
            "Thickness maps on one colour scale", heat,
            f"Per-vertex coating thickness of each variant, same scale 0 to {top:.3g} µm (the largest 99.5th "
            f"percentile; thicker spots saturate). Dashed: the cross-section line."),)),
        Section("section", SECTION_TITLES["section"], figures=(Figure(
            "Thickness cross-section", profile_png(cuts, title=f"section {where}"),
            f"Thickness along the dashed line of the maps, {where}, every variant."),)),
        Section("warnings", SECTION_TITLES["warnings"], warnings_list(document["warnings"])),
        Section("metrics", SECTION_TITLES["metrics"],
                metrics_table(document["variants"], baseline)
                + '<p class="muted">Hover a metric name for its meaning; units and meanings are in the README.</p>'),
        Section("gates", SECTION_TITLES["gates"], gates_table(document["gates"]) + _overall(document["passed"])),
    ]


def warnings_list(warnings: Sequence[Mapping[str, str]]) -> str:
    """The run's warnings (metrics.json ``warnings``), one item each, naming variant and program line."""
    if not warnings:
        return '<p class="muted">No warnings: TOOL as the cell\'s gun, joints within their limits and away from '\
               "singularities, the simulated tool on its commanded path.</p>"
    items = "".join(f"<li><b>{esc(w['variant'])}</b>: {esc(w['message'])}</li>" for w in warnings)
    return f"<ul>{items}</ul>"


def _overall(passed: bool) -> str:
    verdict = '<span class="pass">all gates passed</span>' if passed else '<span class="fail">a gate FAILED</span>'
    return f"<p>Overall: {verdict}</p>"


def write_report(path: Path, loaded, curve, segmentation, runs: Sequence, document: Mapping[str, Any]) -> None:
    """Write the self-contained report.html of a run."""
    sections = build_sections(loaded, curve, segmentation, runs, document)
    subtitle = f"coatsim {__version__}, scenario {loaded.path.name}, {document['mode']} mode"
    write_text(path, render_html(f"coatsim report: {loaded.spec.name}", subtitle, sections))
