"""Deposition efficiency DE: the share of the material landing on the part that sticks there,
as a function of the local spray angle alpha (between the spray ray and the surface; 90 deg is
normal incidence, alpha = 90 deg - the incidence angle gamma). The rest bounces off and is lost.

Two laws, both 1 at normal incidence:

- ``angle`` (the default curve) or ``angle:60=1,45=0.9,...``: piecewise linear in alpha between
  knots (alpha in deg = DE), constant beyond the outermost knots. The default knots follow
  Sandia's impact-angle study (An investigation of the effects of droplet impact angle in
  thermal spray deposition, Sandia National Laboratories, Proc. 7th National Thermal Spray
  Conference 1994, OSTI 160509): from 90 deg out to 60 deg the changes in deposition efficiency
  were small and often statistically insignificant, some significant changes began at 45 deg, and
  at 30 deg deposition efficiency fell for nearly all materials and processes. The study's
  abstract gives no magnitudes; 0.9 at 45 deg and 0.75 at 30 deg are this model's assumption, of
  the order of the extra loss over the geometric cosine measured for HVOF WC-17Co (Katranidis et
  al., J. Therm. Spray Technol. 2018, doi 10.1007/s11666-018-0739-6: thickness / sin alpha relative
  to normal spraying 0.84 at 45 deg, 0.83 at 29 deg); DE falls to 0 at grazing incidence.
  Calibrate with ``table:FILE.csv`` (columns ``spray_angle_deg,efficiency``).
- ``cosine:n=N``: DE = cos^(N-1) gamma, so the deposit follows cos^N gamma (N = 1: no loss; thermal
  spray data fit N = 1.5 to 2, see the research notes on the deposition model).
"""

from __future__ import annotations

import csv
import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coatsim.core.errors import InputError, shown
from coatsim.core.fileio import read_input

#: Knots (spray angle deg, DE) of the default ``angle`` curve; see the module docstring.
DEFAULT_ANGLE_KNOTS: tuple[tuple[float, float], ...] = ((0.0, 0.0), (30.0, 0.75), (45.0, 0.9), (60.0, 1.0), (90.0, 1.0))
#: Below this spray angle a vertex counts as sprayed too flat (the study's first significant changes).
LOW_SPRAY_ANGLE_DEG = 60.0


class Efficiency(ABC):
    """A deposition-efficiency law DE(spray angle) with values in [0, 1]."""

    @abstractmethod
    def factor(self, cos_gamma: np.ndarray) -> np.ndarray:
        """DE at incidence cosines ``cos_gamma`` (cosine of the angle between the ray and the normal)."""

    @property
    @abstractmethod
    def spec(self) -> str:
        """Canonical spec string that ``parse_efficiency_spec`` turns back into this law."""


@dataclass(frozen=True)
class CosinePower(Efficiency):
    """DE = cos^(n-1) gamma."""

    n: float

    def factor(self, cos_gamma: np.ndarray) -> np.ndarray:
        return cos_gamma ** (self.n - 1.0)

    @property
    def spec(self) -> str:
        return f"cosine:n={self.n:g}"


@dataclass(frozen=True)
class AngleTable(Efficiency):
    """DE piecewise linear in the spray angle between ``knots`` (deg, DE), increasing in angle;
    ``source`` is the table file, or empty for knots given inline."""

    knots: tuple[tuple[float, float], ...]
    source: str = ""

    def factor(self, cos_gamma: np.ndarray) -> np.ndarray:
        alpha = np.degrees(np.arcsin(np.clip(cos_gamma, 0.0, 1.0)))  # spray angle = 90 deg - gamma
        angle, value = zip(*self.knots)
        return np.interp(alpha, angle, value)

    @property
    def spec(self) -> str:
        if self.source:
            return f"table:{self.source}"
        if self.knots == DEFAULT_ANGLE_KNOTS:
            return "angle"
        return "angle:" + ",".join(f"{a:g}={v:g}" for a, v in self.knots)


def _knots(pairs: list[tuple[float, float]], where: str) -> tuple[tuple[float, float], ...]:
    """Knots sorted by angle, checked: angles in [0, 90] deg and distinct, values in [0, 1]."""
    pairs = sorted(pairs)
    for angle, value in pairs:
        if not (math.isfinite(angle) and 0.0 <= angle <= 90.0):
            raise InputError(f"{where}: spray angle must be between 0 and 90 deg, found {angle:g}")
        if not (math.isfinite(value) and 0.0 <= value <= 1.0):
            raise InputError(f"{where}: efficiency must be between 0 and 1, found {value:g} at {angle:g} deg")
    angles = [a for a, _ in pairs]
    if not pairs or len(set(angles)) != len(angles):
        raise InputError(f"{where}: give each spray angle once, at least one (spray angle deg = efficiency)")
    return tuple(pairs)


def load_efficiency_table(path: str | Path) -> AngleTable:
    """Read a ``spray_angle_deg,efficiency`` CSV (one knot per row, any order)."""
    path = Path(path)
    try:
        rows = list(csv.reader(read_input(path, "efficiency table").decode("utf-8").splitlines()))
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: cannot read efficiency table ({exc})") from None
    header = [h.strip() for h in rows[0]] if rows else []
    if header != ["spray_angle_deg", "efficiency"]:
        found = ", ".join(shown(h, names=True) for h in header[:3]) or "nothing"
        raise InputError(f"{path}:1: efficiency table header must be 'spray_angle_deg,efficiency', found {found}")
    pairs = []
    for line, row in enumerate(rows[1:], start=2):
        try:
            angle, value = (float(x) for x in row)
        except ValueError:
            raise InputError(f"{path}:{line}: expected two numbers spray_angle_deg,efficiency, found "
                             f"{', '.join(shown(x) for x in row[:3]) or 'nothing'}") from None
        pairs.append((angle, value))
    return AngleTable(_knots(pairs, str(path)), str(path))


def parse_efficiency_spec(spec: str) -> Efficiency | None:
    """DE law from ``none`` (every particle that lands sticks: None), ``angle`` (the default
    curve), ``angle:60=1,45=0.9,30=0.75`` (knots, deg = DE), ``table:FILE.csv`` or ``cosine:n=2``."""
    kind, _, body = spec.strip().partition(":")
    kind, body = kind.strip().lower(), body.strip()
    where = f"deposition efficiency {spec!r}"
    if kind == "none" and not body:
        return None
    if kind == "table":
        if not body:
            raise InputError(f"{where}: give the table file as table:PATH.csv")
        return load_efficiency_table(body)
    if kind == "angle":
        if not body:
            return AngleTable(DEFAULT_ANGLE_KNOTS)
        pairs = []
        for item in filter(None, (x.strip() for x in body.split(","))):
            angle, _, value = item.partition("=")
            try:
                pairs.append((float(angle), float(value)))
            except ValueError:
                raise InputError(f"{where}: knots are spray_angle_deg=efficiency, found {item!r}") from None
        return AngleTable(_knots(pairs, where))
    if kind == "cosine":
        key, eq, text = body.partition("=")
        try:
            n = float(text) if eq and key.strip().lower() == "n" else math.nan
        except ValueError:
            n = math.nan
        if not (math.isfinite(n) and n >= 1):
            raise InputError(f"{where}: expected cosine:n=N with N >= 1 (DE = cos^(N-1) of the incidence angle)")
        return CosinePower(n)
    raise InputError(f"{where}: unknown law {kind!r}; use none, angle, angle:DEG=DE,..., table:FILE.csv or cosine:n=N")
