"""The verdict of a run: what the polysegment wins and loses against each polyline variant.

A pure function of the metrics document (``metrics.json``): for every polyline variant that ran
beside the polysegment, and for each headline metric — cycle time, lowest speed where the curve
allows the speed, fraction at speed, thickness CV, thick spots — the polysegment's value, the
polyline's, the relative change in % (polysegment against polyline) and the outcome. A change
counts as a tie when it is within TIE_RELATIVE of the polyline's value or within the metric's
absolute resolution (whichever is larger): differences smaller than that are numerical noise of
the twin, not a property of the program. Rendering is up to the caller.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal, Mapping, Optional

BASELINE = "polysegment"
TIE_RELATIVE = 0.02  # changes within 2 % of the polyline's value are ties

Outcome = Literal["win", "loss", "tie", "undefined"]


@dataclass(frozen=True)
class Criterion:
    """A headline metric: its key, what people call it, which direction is better, and the
    absolute difference below which two values count as equal."""

    key: str
    label: str
    higher_is_better: bool
    resolution: float


CRITERIA: tuple[Criterion, ...] = (
    Criterion("motion.cycle_time_s", "cycle time", False, 0.002),
    Criterion("motion.min_speed_ratio", "lowest speed", True, 0.005),
    Criterion("motion.fraction_at_speed", "fraction at speed", True, 0.005),
    Criterion("coating.thickness_cv", "thickness CV", False, 0.002),
    Criterion("coating.thick_spot_fraction", "thick spots", False, 0.005),
)


@dataclass(frozen=True)
class MetricOutcome:
    """One metric against one polyline: values, the change in % (None when the polyline's
    value is 0 or either is undefined) and the outcome for the polysegment."""

    criterion: Criterion
    polysegment: Optional[float]
    polyline: Optional[float]
    change_pct: Optional[float]
    outcome: Outcome


@dataclass(frozen=True)
class Comparison:
    """The polysegment against one polyline variant."""

    against: str
    outcomes: tuple[MetricOutcome, ...]

    def by(self, outcome: Outcome) -> tuple[MetricOutcome, ...]:
        return tuple(o for o in self.outcomes if o.outcome == outcome)

    @property
    def headline(self) -> str:
        """One line: the wins and the losses with their changes, then the ties."""
        parts = []
        for outcome, verb in (("win", "wins"), ("loss", "loses")):
            found = self.by(outcome)
            parts.append(f"{verb} " + ", ".join(f"{o.criterion.label} ({change_text(o)})" for o in found)
                         if found else f"{verb} nothing")
        ties = self.by("tie")
        if ties:
            parts.append("ties " + ", ".join(o.criterion.label for o in ties))
        undefined = self.by("undefined")
        if undefined:
            parts.append("cannot compare " + ", ".join(o.criterion.label for o in undefined))
        return f"Against {self.against}, the polysegment " + "; ".join(parts) + "."


@dataclass(frozen=True)
class Verdict:
    """Every comparison of a run (empty when the polysegment or every polyline is missing)."""

    comparisons: tuple[Comparison, ...]


def _number(variant: Mapping[str, Any], key: str) -> Optional[float]:
    group, name = key.split(".")
    value = variant.get(group, {}).get(name)
    if value is None or isinstance(value, bool):
        return None
    value = float(value)
    return None if math.isnan(value) else value


def change_text(o: MetricOutcome) -> str:
    """The change as people read it: "-12.3 %", "563x" beyond +1000 %, or both values when
    there is no ratio (the polyline's value is 0) or a value is undefined."""
    if o.change_pct is None:
        return f"{_value(o.polysegment)} vs {_value(o.polyline)}"
    if o.change_pct >= 1000.0:
        return f"{o.polysegment / o.polyline:.0f}x"
    return f"{o.change_pct:+.1f} %"


def _value(x: Optional[float]) -> str:
    return "undefined" if x is None else f"{x:.3g}"


def compare(criterion: Criterion, mine: Optional[float], theirs: Optional[float]) -> MetricOutcome:
    """The outcome of one metric (see the module docstring for the tie rule)."""
    if mine is None or theirs is None:
        return MetricOutcome(criterion, mine, theirs, None, "undefined")
    change = None if theirs == 0.0 else 100.0 * (mine - theirs) / abs(theirs)
    if abs(mine - theirs) <= max(TIE_RELATIVE * abs(theirs), criterion.resolution):
        return MetricOutcome(criterion, mine, theirs, change, "tie")
    better = (mine > theirs) == criterion.higher_is_better
    return MetricOutcome(criterion, mine, theirs, change, "win" if better else "loss")


def verdict(document: Mapping[str, Any]) -> Verdict:
    """The verdict of a metrics document: the polysegment against every other variant, in the
    document's order."""
    variants = document["variants"]
    if BASELINE not in variants:
        return Verdict(())
    mine = variants[BASELINE]
    return Verdict(tuple(
        Comparison(name, tuple(compare(c, _number(mine, c.key), _number(other, c.key)) for c in CRITERIA))
        for name, other in variants.items() if name != BASELINE
    ))


def advantage_pct(o: MetricOutcome) -> Optional[float]:
    """The change in % signed so that positive is better for the polysegment (a shorter cycle
    time or a lower CV count as positive); None when there is no ratio."""
    if o.change_pct is None:
        return None
    return o.change_pct if o.criterion.higher_is_better else -o.change_pct


def overall(result: Verdict) -> str:
    """One sentence over every comparison, worded from the outcomes: a loss is called a loss."""
    if not result.comparisons:
        return "No polyline variant ran beside the polysegment: there is nothing to compare."
    names = ", ".join(c.against for c in result.comparisons)
    losses = [(c.against, o) for c in result.comparisons for o in c.by("loss")]
    wins = sum(len(c.by("win")) for c in result.comparisons)
    if not losses and wins:
        every = "every polyline variant" if len(result.comparisons) > 1 else names
        return (f"The polysegment wins or ties every measure against {every} "
                f"({wins} win{'s' if wins != 1 else ''}, no loss).")
    if not losses:
        return "No measure tells the variants apart: every one is a tie or cannot be compared."
    lost = "; ".join(f"{o.criterion.label} against {name} ({change_text(o)})" for name, o in losses)
    if not wins:
        return f"The polysegment loses: it wins no measure and loses {lost}."
    return (f"A mixed result: the polysegment wins {wins} and loses {len(losses)} of the comparisons with "
            f"{names}; it loses {lost}.")
