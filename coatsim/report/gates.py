"""CI gates: pass/fail checks of one metric of one variant, against a number or against the
same metric of another variant (times a factor), or of several: then the gate must hold against
each of them, i.e. against the best one (the strictest reference: the smallest for ``<`` and
``<=``, the largest for ``>`` and ``>=``).
"""

from __future__ import annotations

import math
import operator
from dataclasses import asdict, dataclass
from typing import Any, Callable, Mapping, Optional, Protocol, Sequence, Union

from coatsim.core.errors import InputError

OPERATORS: dict[str, Callable[[float, float], bool]] = {
    "<": operator.lt,
    "<=": operator.le,
    ">": operator.gt,
    ">=": operator.ge,
    "==": operator.eq,
}

Variants = Mapping[str, Mapping[str, Mapping[str, Any]]]


class GateLike(Protocol):
    """What a gate needs (the scenario's GateSpec satisfies it)."""

    metric: str
    variant: str
    op: str
    threshold: Optional[float]
    compare_to: Optional[Union[str, Sequence[str]]]
    factor: float


@dataclass(frozen=True)
class GateResult:
    """One evaluated gate: ``value op reference`` where reference is the threshold or
    ``factor`` times the compared variant's value (with several compared variants, the
    strictest of them, from ``reference_variant``)."""

    metric: str
    variant: str
    op: str
    value: Optional[float]
    reference: Optional[float]
    threshold: Optional[float]
    compare_to: Optional[Union[str, tuple[str, ...]]]
    factor: float
    passed: bool
    reference_variant: Optional[str] = None

    @property
    def label(self) -> str:
        if self.compare_to is None:
            rhs = f"{self.threshold:g}"
        else:
            other = self.compare_to if isinstance(self.compare_to, str) else f"best of ({', '.join(self.compare_to)})"
            rhs = other if self.factor == 1.0 else f"{self.factor:g} x {other}"
        return f"{self.metric} [{self.variant}] {self.op} {rhs}"

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def metric_value(variants: Variants, variant: str, metric: str) -> Optional[float]:
    """The value of ``group.name`` for ``variant`` (None when not defined for it).

    An unknown variant, group or name raises InputError listing what exists.
    """
    if variant not in variants:
        raise InputError(f"gate: variant {variant!r} was not run (ran: {', '.join(variants)})")
    group, _, name = metric.partition(".")
    groups = variants[variant]
    if group not in groups or name not in groups[group]:
        known = sorted(f"{g}.{n}" for g, values in groups.items() for n in values)
        raise InputError(f"gate: unknown metric {metric!r}; known metrics: {', '.join(known)}")
    value = groups[group][name]
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"gate: metric {metric!r} is not a number ({value!r}); gate on a numeric metric")
    return float(value)


def _strictest(op: str, value: Optional[float], references: Sequence[tuple[str, Optional[float]]]) -> tuple[Optional[str], Optional[float]]:
    """The compared (variant, reference) that decides the gate: an undefined one if any, the
    smallest for < and <=, the largest for > and >=, for == the first one that differs."""
    for name, ref in references:
        if ref is None or math.isnan(ref):
            return name, None
    if op in ("<", "<="):
        return min(references, key=lambda r: r[1])
    if op in (">", ">="):
        return max(references, key=lambda r: r[1])
    return next((r for r in references if value is None or r[1] != value), references[0])


def evaluate_gate(gate: GateLike, variants: Variants) -> GateResult:
    """Evaluate one gate; a metric that is undefined (None or NaN) fails the gate."""
    value = metric_value(variants, gate.variant, gate.metric)
    compare = gate.compare_to
    source: Optional[str] = None
    if compare is None:
        reference = None if gate.threshold is None else float(gate.threshold)
    else:
        names = (compare,) if isinstance(compare, str) else tuple(compare)
        if not names:
            raise InputError("gate: compare_to names no variant")
        scaled = [(n, None if (v := metric_value(variants, n, gate.metric)) is None else gate.factor * v) for n in names]
        source, reference = _strictest(gate.op, value, scaled)
        compare = compare if isinstance(compare, str) else names
    defined = value is not None and reference is not None and not (math.isnan(value) or math.isnan(reference))
    passed = bool(defined and OPERATORS[gate.op](value, reference))
    return GateResult(
        metric=gate.metric, variant=gate.variant, op=gate.op, value=value, reference=reference,
        threshold=gate.threshold, compare_to=compare, factor=gate.factor, passed=passed,
        reference_variant=source,
    )


def evaluate_gates(gates: Sequence[GateLike], variants: Variants) -> list[GateResult]:
    """Evaluate every gate in order."""
    return [evaluate_gate(g, variants) for g in gates]
