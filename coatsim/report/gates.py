"""CI gates: pass/fail checks of one metric of one variant, against a number or against the
same metric of another variant (times a factor).
"""

from __future__ import annotations

import math
import operator
from dataclasses import asdict, dataclass
from typing import Any, Callable, Mapping, Optional, Protocol, Sequence

from coatsim.errors import InputError

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
    compare_to: Optional[str]
    factor: float


@dataclass(frozen=True)
class GateResult:
    """One evaluated gate: ``value op reference`` where reference is the threshold or
    ``factor`` times the compared variant's value."""

    metric: str
    variant: str
    op: str
    value: Optional[float]
    reference: Optional[float]
    threshold: Optional[float]
    compare_to: Optional[str]
    factor: float
    passed: bool

    @property
    def label(self) -> str:
        if self.compare_to is None:
            rhs = f"{self.threshold:g}"
        else:
            rhs = self.compare_to if self.factor == 1.0 else f"{self.factor:g} x {self.compare_to}"
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


def evaluate_gate(gate: GateLike, variants: Variants) -> GateResult:
    """Evaluate one gate; a metric that is undefined (None or NaN) fails the gate."""
    value = metric_value(variants, gate.variant, gate.metric)
    if gate.compare_to is None:
        reference = None if gate.threshold is None else float(gate.threshold)
    else:
        other = metric_value(variants, gate.compare_to, gate.metric)
        reference = None if other is None else gate.factor * other
    defined = value is not None and reference is not None and not (math.isnan(value) or math.isnan(reference))
    passed = bool(defined and OPERATORS[gate.op](value, reference))
    return GateResult(
        metric=gate.metric, variant=gate.variant, op=gate.op, value=value, reference=reference,
        threshold=gate.threshold, compare_to=gate.compare_to, factor=gate.factor, passed=passed,
    )


def evaluate_gates(gates: Sequence[GateLike], variants: Variants) -> list[GateResult]:
    """Evaluate every gate in order."""
    return [evaluate_gate(g, variants) for g in gates]
