"""The console summary of a run: the headline comparison table, the verdict per polyline and the
gate results."""

from __future__ import annotations

from typing import Any, Mapping

from coatsim.report.catalogue import METRICS
from coatsim.report.html import fmt
from coatsim.report.verdict import verdict

HEADLINE = (
    "motion.cycle_time_s",
    "motion.min_speed_ratio",
    "motion.fraction_at_speed",
    "motion.stops",
    "coating.thickness_cv",
    "coating.thick_spot_fraction",
)


def headline_rows(document: Mapping[str, Any]) -> list[tuple[str, list[Any]]]:
    """The comparison a run leads with: (metric, value per variant) rows."""
    variants = document["variants"]
    rows = []
    for key in HEADLINE:
        group, name = key.split(".")
        rows.append((key, [variants[v][group][name] for v in variants]))
    return rows


def gate_line(gate: Mapping[str, Any]) -> str:
    """One gate's line of the summary: PASS or FAIL, its label, its value and its reference."""
    return f"{'PASS' if gate['passed'] else 'FAIL'}  {gate['label']}  (value {fmt(gate['value'])}, reference {fmt(gate['reference'])})"


def summary_text(document: Mapping[str, Any]) -> str:
    """Fixed-width comparison table, then one line per gate and the verdict."""
    names = list(document["variants"])
    label = [f"{key} ({METRICS[key].unit})" for key in HEADLINE]
    width = max(len(x) for x in label)
    cols = [max(len(n), 10) for n in names]
    lines = [" " * width + "".join(f"  {n:>{c}}" for n, c in zip(names, cols))]
    for text, (_, values) in zip(label, headline_rows(document)):
        lines.append(f"{text:<{width}}" + "".join(f"  {fmt(v):>{c}}" for v, c in zip(values, cols)))
    comparisons = verdict(document).comparisons
    if comparisons:
        lines.append("")
        lines.extend(c.headline for c in comparisons)
    gates = document["gates"]
    if gates:
        lines.append("")
        for g in gates:
            lines.append(gate_line(g))
        failed = sum(not g["passed"] for g in gates)
        lines.append(f"gates: {len(gates) - failed} of {len(gates)} passed")
    return "\n".join(lines)
