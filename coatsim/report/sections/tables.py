"""The closing sections: every metric with its human name and unit (percent where a fraction,
a ratio to the polysegment only where a ratio means something), the scenario summary and the
gates."""

from __future__ import annotations

import json
from typing import Any, Mapping, Sequence

from coatsim.report.catalogue import GROUPS, METRICS
from coatsim.report.html import Section, esc, gates_table, key_value_table
from coatsim.report.metric_names import ratio_text, shown, unit, value_text
from coatsim.report.part_section import part_summary

GROUP_TITLES = {"segmentation": "Programmed curve", "motion": "Motion of the simulated arm",
                "coating": "Coating (region of interest all variants share)"}


def metrics_table(variants: Mapping[str, Mapping[str, Mapping[str, Any]]], baseline: str | None) -> str:
    """Every metric for every variant, grouped, with the ratio of each other variant to
    ``baseline`` where it means something."""
    names = list(variants)
    others = [v for v in names if v != baseline] if baseline in variants else []
    head = ('<th class="l">metric</th><th class="l">unit</th>' + "".join(f"<th>{esc(v)}</th>" for v in names)
            + "".join(f"<th>{esc(v)} / {esc(baseline)}</th>" for v in others))
    rows = []
    for group in GROUPS:
        rows.append(f'<tr class="group"><td colspan="{2 + len(names) + len(others)}">{esc(GROUP_TITLES[group])}</td></tr>')
        for key, info in METRICS.items():
            if not key.startswith(group + "."):
                continue
            name = key.split(".", 1)[1]
            value = lambda v: variants[v].get(group, {}).get(name)  # noqa: E731
            cells = "".join(f"<td>{value_text(key, value(v))}</td>" for v in names)
            for v in others:
                cells += f"<td>{ratio_text(key, value(v), value(baseline)) or '–'}</td>"
            rows.append(f'<tr><td class="l" title="{esc(key)}: {esc(info.meaning)}">{esc(shown(key).label)}</td>'
                        f'<td class="l">{esc(unit(key))}</td>{cells}</tr>')
    return f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(rows)}</tbody></table>"


def metrics_section(data: Any) -> Section:
    baseline = data.reference.name
    note = ('<p class="muted">Hover a name for the metric\'s key in metrics.json and its meaning (also in the metrics reference of the documentation). '
            "Fractions and ratios of like quantities are shown in %. The ratio columns divide each variant's value by "
            f"the {esc(baseline)}'s where that means something (times, speeds, lengths, thickness, counts of moves); "
            "'–' elsewhere.</p>")
    return Section("metrics", "All metrics", metrics_table(data.document["variants"], baseline) + note)


def summary_rows(data: Any) -> list[tuple[str, Any]]:
    """The scenario at a glance: inputs, workpiece, robot, gun, motion, variants, mode."""
    spec, document, loaded = data.spec, data.document, data.loaded
    c = spec.curve
    if c is None:
        source = f"the sprayed path of program variant {spec.programs[0].name}"
    else:
        source = f"built-in {c.builtin} {json.dumps(c.params, sort_keys=True)}" if c.builtin else f"file {c.file}"
    placed = "" if c is None else f"; scale {c.scale:g}, rotated {c.rotate_deg:g} deg"
    curve = data.contours[0].curve
    wp = spec.workpiece
    size = {"plate": lambda: f"plate {wp.size_mm[0]:g} x {wp.size_mm[1]:g} mm",
            "cylinder": lambda: f"cylinder R {wp.radius_mm:g} x L {wp.length_mm:g} mm, axis {wp.axis}",
            "mesh": lambda: f"mesh {wp.file}"}[wp.kind]()
    spacing = spec.fast.coating_spacing_mm if document["mode"] == "fast" else spec.coating.spacing_mm
    rows = [
        ("scenario file", loaded.path.name),
        ("description", spec.description or "–"),
        ("curve", f"{source}{placed}; " + (part_summary(data.contours) if len(data.contours) > 1 else
                  f"{'closed' if curve.closed else 'open'}, {len(curve.points)} points, {curve.length:.1f} mm")),
        ("segmentation", f"tolerance {spec.segmentation.tolerance_mm:g} mm, method {spec.segmentation.method}, "
                         f"corners above {spec.segmentation.corner_deg:g} deg"),
        ("workpiece", f"{size} at {wp.pose.position_mm} mm, O-A-T {wp.pose.oat_deg} deg"),
        ("robot", spec.robot.model),
        ("gun", f"{spec.gun.footprint}, Q {spec.gun.flow_mm3_s:g} mm³/s, stand-off {spec.gun.standoff_mm:g} mm, "
                f"target {spec.gun.target_thickness_um:g} µm"),
        ("motion", f"{spec.motion.speed_mm_s:g} mm/s, accuracy {spec.motion.accuracy_mm:g} mm, run-in "
                   f"{spec.motion.lead_in_mm:g} mm, run-out {spec.motion.lead_out_mm:g} mm"),
        ("variants", variant_list(spec, data.runs)),
        ("mode", f"{document['mode']} (coating mesh {spacing:g} mm)"),
    ]
    seg = document["variants"].get("polysegment", {}).get("segmentation")
    if seg is not None:
        rows.insert(4, ("polysegment", f"{seg['n_lines']} lines + {seg['n_arcs']} arcs, deviation "
                                       f"{seg['max_deviation_mm']:.4g} mm"))
    return rows


def summary_section(data: Any) -> Section:
    notes = "".join(f'<p class="muted">{esc(n)}</p>' for n in data.notes)
    return Section("summary", "Scenario", key_value_table(summary_rows(data)) + notes)


def overall(passed: bool) -> str:
    verdict = '<span class="pass">all gates passed</span>' if passed else '<span class="fail">a gate FAILED</span>'
    return f"<p>Overall: {verdict}</p>"


def gates_section(gates: Sequence[Mapping[str, Any]], passed: bool) -> Section:
    return Section("gates", "Gates", gates_table(gates) + overall(passed))


def variant_list(spec: Any, runs: Any) -> str:
    """The variants' names, each with its own programmed speed where it has one."""
    return ", ".join(r.name + ("" if spec.speed_of(r.name) == spec.motion.speed_mm_s else
                               f" (programmed at {spec.speed_of(r.name):g} mm/s)") for r in runs)
