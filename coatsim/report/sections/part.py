"""The sections of a report on a 3-D part that differ from a curve's: the spray spot's speed
along each pass, the thickness histogram over the region with the specification band, the maps
on the part (thickness per variant on one scale, spray angle, stand-off), the plan and the
programs, and the scenario at a glance. Each reads the run's results and metrics document only."""

from __future__ import annotations

from typing import Any

import numpy as np

from coatsim.report.html import Figure, Section, esc, figure_html, fmt, key_value_table
from coatsim.report.plots import bar_ticks, colour, figure, grid, png_bytes, title
from coatsim.report.sections.tables import variant_list
from coatsim.spray.efficiency import LOW_SPRAY_ANGLE_DEG

HISTOGRAM_BINS = 60
SPEED_POINTS = 4000  # samples per variant drawn on the speed plot, at most


def _curve_rows(execution: Any) -> list[np.ndarray]:
    """Per pass, the log's rows on its curve proper with the gun open."""
    log = execution.log
    spray = np.asarray(log.spray, bool)
    return [np.flatnonzero((log.progress >= a) & (log.progress <= b) & spray) for a, b in execution.curves]


def speed_figure(data: Any) -> bytes:
    """Per variant, the spray spot's speed along the passes one after the other (pass borders dotted)."""
    runs = data.runs
    fig = figure(11.0, 1.0 + 1.6 * len(runs))
    axes = grid(fig, len(runs), 1, margins=(0.8, 0.25, 0.35, 0.5), gaps=(0.4, 0.45), sharex=True)[:, 0]
    for k, (ax, run) in enumerate(zip(axes, runs)):
        log, offset, target = run.execution.log, 0.0, data.spec.speed_of(run.name)
        along, speed, borders = [], [], []  # the passes in one line, broken (NaN) between them
        for rows in _curve_rows(run.execution):
            if not len(rows):
                continue
            rows = rows[:: max(1, len(rows) * len(run.execution.curves) // SPEED_POINTS)]
            s = log.progress[rows] - log.progress[rows[0]] + offset
            along += [s, [np.nan]]
            speed += [log.spot_speed[rows], [np.nan]]
            offset = float(s[-1])
            borders.append(offset)
        if along:
            ax.plot(np.concatenate(along), np.concatenate(speed), color=colour(run.name, k), lw=0.8)
        ax.vlines(borders, 0.0, 1.0, transform=ax.get_xaxis_transform(), colors="#999999", lw=0.5, linestyles=":")
        ax.axhline(target, color="#333333", lw=0.6, ls="--")
        ax.set_ylim(0.0, 1.25 * target)
        ax.set_ylabel("mm/s", fontsize=8)
        title(ax, f"{run.name}: spray spot speed on the surface", loc="left")
    axes[-1].set_xlabel("along the passes, one after the other (mm)", fontsize=8)
    return png_bytes(fig)


def passes_table(document: Any) -> str:
    """Per pass and variant: cycle time, lowest speed ratio, the spot's lowest speed ratio, stops."""
    rows = document.get("passes", [])
    if not rows:
        return ""
    variants = list(document["variants"])
    cols = (("cycle_time_s", "cycle s"), ("min_speed_ratio", "lowest v"), ("spot_min_ratio", "spot lowest v"),
            ("stops", "stops"))
    head = "<tr><th>pass</th><th>length mm</th>" + "".join(
        f"<th>{esc(v)}: {h}</th>" for v in variants for _, h in cols) + "</tr>"
    body = "".join(
        f"<tr><td>{r['pass']}</td><td>{fmt(r['planned_length_mm'])}</td>"
        + "".join(f"<td>{fmt(r['variants'].get(v, {}).get(key))}</td>" for v in variants for key, _ in cols) + "</tr>"
        for r in rows)
    return f"<table>{head}{body}</table>"


def speed_section(data: Any) -> Section:
    body = figure_html(Figure(
        "The spray spot's speed along each pass", speed_figure(data),
        "The speed at which the spray spot (the tool centre point plus the stand-off along the spray axis) moves on "
        "the part, over the sprayed passes proper one after the other (leads and travel left out; dotted lines: the "
        "border between two passes); dashed: the programmed speed. The coat is thicker where the spot is slower."))
    body += ('<p class="muted">Per pass (ratios of the programmed speed; "lowest v" where the curve allows the speed):'
             "</p>" + passes_table(data.document))
    return Section("speed", "Speed along the passes", body)


def histogram_figure(data: Any) -> bytes:
    """Area-weighted thickness histogram of every variant over the shared region, spec band shaded."""
    spec = data.document["variants"][data.reference.name]["coating"]
    target, tol = spec["target_um"], spec["tolerance_pct"]
    top = data.scale_um[1]
    fig = figure(9.0, 3.4)
    ax = grid(fig, 1, 1, margins=(0.8, 2.6, 0.35, 0.55))[0, 0]  # the legend right of the axes
    ax.axvspan(target * (1 - tol / 100), target * (1 + tol / 100), color="#2ca02c", alpha=0.15, lw=0)
    ax.axvline(target, color="#2ca02c", lw=0.8)
    bins = np.linspace(0.0, max(top, target * (1 + tol / 100)) * 1.05, HISTOGRAM_BINS + 1)
    for k, run in enumerate(data.runs):
        roi = run.coating.roi
        share = data.document["variants"][run.name]["coating"]["within_spec_fraction"]
        w = run.coating.surface.areas[roi]
        ax.hist(np.clip(run.coating.thickness_um[roi], 0.0, bins[-1]), bins=bins, weights=100 * w / w.sum(),
                histtype="step", lw=1.2, color=colour(run.name, k), label=f"{run.name}: {100 * share:.1f} % in spec")
    ax.set_xlabel("thickness (µm)", fontsize=8)
    ax.set_ylabel("share of the region's area (%)", fontsize=8)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7.5, frameon=False)
    title(ax, f"target {target:g} µm ± {tol:g} %", loc="left")
    return png_bytes(fig)


def histogram_section(data: Any) -> Section:
    return Section("histogram", "Thickness over the region", figure_html(Figure(
        "Thickness histogram over the region of interest", histogram_figure(data),
        "The share of the region's area (the vertices every variant's sprayed band covers, the part's border and the "
        "passes' run-in and run-out left out) at each thickness; green: the specification (coating target ± "
        "tolerance). The legend gives each variant's share inside it (coating.within_spec_fraction).")))


def _view(data: Any) -> tuple[np.ndarray, np.ndarray]:
    """Two orthonormal directions (2, 3) across the region's mean normal (the maps look along it)
    and the normal itself."""
    run = data.reference
    surface, roi = run.coating.surface, run.coating.roi
    normal = (surface.normals[roi] * surface.areas[roi, None]).sum(axis=0)
    normal = normal / max(float(np.linalg.norm(normal)), 1e-12)
    helper = np.eye(3)[int(np.argmin(np.abs(normal)))]
    u = np.cross(helper, normal)
    u /= np.linalg.norm(u)
    return np.vstack([u, np.cross(normal, u)]), normal


def _front(coarse: Any, normal: np.ndarray) -> np.ndarray:
    """The coarse mesh's triangles that face the viewer (the back of a closed part is not drawn
    over its front)."""
    v = coarse.vertices[coarse.faces]
    return coarse.faces[np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]) @ normal > 0]


def maps_figure(data: Any) -> bytes:
    """Thickness of every variant (one scale), then the reference's spray angle and stand-off."""
    coarse = data.coarse
    axes2, normal = _view(data)
    xy = (coarse.vertices - coarse.vertices.mean(axis=0)) @ axes2.T
    faces = _front(coarse, normal)
    panels = len(data.runs) + 2
    cols = min(panels, 3)
    rows = -(-panels // cols)
    fig = figure(11.0, 3.3 * rows)
    axes = grid(fig, rows, cols, margins=(0.2, 0.2, 0.35, 0.2), gaps=(0.7, 0.45)).ravel()
    vmin, vmax = data.scale_um
    ref = data.reference.coating
    angle = np.nan_to_num(ref.deposit.spray_angle_deg, nan=0.0)
    standoff = ref.deposit.standoff_mm
    measured = standoff[ref.roi & np.isfinite(standoff)]
    low, high = (float(measured.min()), float(measured.max())) if len(measured) else (0.0, 1.0)
    fields = [(r.coating.thickness_um, vmin, vmax, "viridis", f"{r.name}: thickness (µm)") for r in data.runs]
    fields += [(angle, 30.0, 90.0, "magma", f"{data.reference.name}: spray angle (deg, 90 = normal)"),
               (np.nan_to_num(standoff, nan=low), low, max(high, low + 1e-3), "cividis",
                f"{data.reference.name}: stand-off where coating landed (mm)")]
    for ax, (values, lo, hi, cmap, label) in zip(axes, fields):
        image = ax.tripcolor(xy[:, 0], xy[:, 1], faces, coarse.field(values), shading="gouraud", cmap=cmap,
                             vmin=lo, vmax=hi, rasterized=True)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xticks([])
        ax.set_yticks([])
        fig.colorbar(image, ax=ax, shrink=0.8, pad=0.02, ticks=bar_ticks()).ax.tick_params(labelsize=7)
        title(ax, label, loc="left", fontsize=8)
    for ax in axes[len(fields):]:
        ax.set_visible(False)
    return png_bytes(fig)


def maps_section(data: Any) -> Section:
    body = figure_html(Figure(
        "Thickness, spray angle and stand-off on the part", maps_figure(data),
        "The part seen along the region's mean normal (its faces turned away not drawn). First each variant's "
        "thickness on the report's one colour scale "
        f"(the 3-D view's), then, for {data.reference.name}, the deposit-weighted spray angle (90 deg: the spray meets "
        f"the surface square on; below {LOW_SPRAY_ANGLE_DEG:g} deg counts in coating.low_angle_fraction; 0 where "
        "nothing landed) and the stand-off at which the coating landed (its scale: the range over the region of "
        "interest)."))
    return Section("maps", "Maps on the part", body)


def program_section(data: Any) -> Section:
    """The plan and each variant's program files."""
    plan = data.document.get("plan", {})
    rows = [("pattern", f"{plan.get('pattern')}: {plan.get('passes')} passes, spacing {fmt(plan.get('spacing_mm'))} mm "
                        f"(ripple {fmt(plan.get('ripple_pct'))} %), stand-off {fmt(plan.get('standoff_mm'))} mm"),
            ("region", f"{fmt(plan.get('region_area_mm2'))} mm², {fmt(100 * (plan.get('coverage') or 0.0))} % within "
                       "half a spacing of a pass"),
            ("passes file", "paths.json (coatsim.surfacepaths/1)")]
    for r in data.runs:
        seg = data.document["variants"][r.name]["segmentation"]
        rows.append((r.name, f"{r.program_file}: {seg['n_lines']} lines + {seg['n_arcs']} arcs in 3-D, deviation from "
                             f"the planned tool points {fmt(seg['max_deviation_mm'])} mm"))
    notes = "".join(f'<p class="muted">{esc(n)}</p>' for n in plan.get("notes", []))
    return Section("program", "Plan and programs", key_value_table(rows) + notes)


def summary_section(data: Any) -> Section:
    spec, document = data.spec, data.document
    part, paths = spec.part, spec.planned
    region = part.region
    where = ("all faces" if region.all else f"box {region.box}" if region.box is not None else
             f"faces within {region.max_angle_deg:g} deg of {region.facing or 'the default side'}")
    spacing = spec.fast.coating_spacing_mm if document["mode"] == "fast" else spec.coating.spacing_mm
    rows = [
        ("scenario file", data.loaded.path.name),
        ("description", spec.description or "–"),
        ("part", f"{part.mesh} ({part.units}) at {part.pose} (x, y, z mm, O, A, T deg); region: {where}"),
        ("passes", f"{paths.pattern}, speed on the {paths.speed_on}, axis within {paths.angle_tol_deg:g} deg"),
        ("gun", f"{spec.gun.footprint}, Q {spec.gun.flow_mm3_s:g} mm³/s, stand-off {data.standoff_mm:g} mm, target "
                f"{spec.gun.target_thickness_um:g} µm, efficiency {spec.gun.efficiency}"),
        ("motion", f"{spec.motion.speed_mm_s:g} mm/s, accuracy {spec.motion.accuracy_mm:g} mm"),
        ("variants", variant_list(spec, data.runs)),
        ("mode", f"{document['mode']} (coating mesh {spacing:g} mm, {data.surface.n_vertices} vertices)"),
    ]
    notes = "".join(f'<p class="muted">{esc(n)}</p>' for n in data.notes)
    return Section("summary", "Scenario", key_value_table(rows) + notes)
