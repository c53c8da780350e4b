"""Named parametric test curves, sampled uniformly by arc length (mm), every point on the curve.

``builtin_curve("ellipse", a=120)`` or, from the command line, ``builtin:ellipse:a=120,points=3000``.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from coatsim.core.budgets import check_budget
from coatsim.core.errors import InputError
from coatsim.geometry.curves import ClosedMode, Curve, make_curve
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.geometry.primitives import Line

DEFAULT_POINTS = 3000


ARC_GRID = 16384  # parameter intervals of the arc-length table (5-point Gauss–Legendre each)


def _by_arc_length(f: Callable[[np.ndarray], np.ndarray], t0: float, t1: float, n: int) -> np.ndarray:
    """``n`` points of the curve ``f`` (parameter t0 -> t1) equally spaced in arc length,
    every one on the curve itself: the arc length s(t) is integrated on a fixed parameter
    grid (speed by central differences) and t(s) interpolated between the grid nodes by
    cubic Hermite pieces with the exact slope dt/ds = 1/speed (monotone pieces where the
    curve stops, e.g. at a cusp)."""
    from scipy.interpolate import CubicHermiteSpline, PchipInterpolator

    h = 2e-6 * (t1 - t0)

    def speed(t: np.ndarray) -> np.ndarray:
        v = (f(t + h) - f(t - h)) / (2 * h)
        return np.hypot(v[:, 0], v[:, 1])

    t = np.linspace(t0, t1, ARC_GRID + 1)
    nodes, weights = np.polynomial.legendre.leggauss(5)
    half = (t1 - t0) / ARC_GRID / 2
    tn = ((t[:-1] + t[1:]) / 2)[:, None] + half * nodes
    s = np.concatenate(([0.0], np.cumsum(speed(tn.ravel()).reshape(tn.shape) @ weights * half)))
    at_nodes = speed(t)
    if at_nodes.min() > 1e-9 * at_nodes.mean():
        t_of_s = CubicHermiteSpline(s, t, 1.0 / at_nodes)
    else:
        moving = np.r_[True, np.diff(s) > 0]  # a stop would repeat an arc length
        t_of_s = PchipInterpolator(s[moving], t[moving])
    u = t_of_s(np.linspace(0.0, s[-1], n))
    u[0], u[-1] = t0, t1
    return f(u)


def paper_spiral(points: int = DEFAULT_POINTS, width: float = 200.0, turns: float = 2.0) -> np.ndarray:
    """The paper's Fig. 6: x = -(1+2t) cos t, y = (1+2t) sin t, t in [0, 2π·turns]."""
    f = lambda t: np.column_stack((-(1 + 2 * t) * np.cos(t), (1 + 2 * t) * np.sin(t)))  # noqa: E731
    xy = _by_arc_length(f, 0.0, 2 * math.pi * turns, points)
    return xy * (width / np.ptp(xy[:, 0]))


def ellipse(points: int = DEFAULT_POINTS, a: float = 100.0, b: float = 50.0) -> np.ndarray:
    f = lambda t: np.column_stack((a * np.cos(t), b * np.sin(t)))  # noqa: E731
    return _by_arc_length(f, 0.0, 2 * math.pi, points)


def naca(points: int = DEFAULT_POINTS, code: str = "0012", chord: float = 200.0) -> np.ndarray:
    """NACA 4-digit airfoil (closed trailing edge): TE -> upper -> LE -> lower -> TE."""
    code = str(code).zfill(4)
    if len(code) != 4 or not code.isdigit():
        raise InputError(f"builtin:naca: code must be 4 digits, got {code!r}")
    m, p, tt = int(code[0]) / 100, int(code[1]) / 10, int(code[2:]) / 100

    def surface(u: np.ndarray) -> np.ndarray:
        """u in [0, π]: upper surface TE -> LE for u <= π/2, lower LE -> TE after; the chord
        position x = 1 - cos|u - π/2| (written 2 sin²(·/2), exact near 0) keeps both the leading edge (x ~ u²) and the trailing
        edge (dx/du = 1) regular in u."""
        x = 2 * np.sin(np.abs(u - math.pi / 2) / 2) ** 2
        yt = 5 * tt * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1036 * x**4)
        if m > 0 and p > 0:
            yc = np.where(x < p, m / p**2 * (2 * p * x - x**2), m / (1 - p) ** 2 * (1 - 2 * p + 2 * p * x - x**2))
            dyc = np.where(x < p, 2 * m / p**2 * (p - x), 2 * m / (1 - p) ** 2 * (p - x))
        else:
            yc, dyc = np.zeros_like(x), np.zeros_like(x)
        th = np.arctan(dyc)
        side = np.where(u <= math.pi / 2, 1.0, -1.0)
        return chord * np.column_stack((x - side * yt * np.sin(th), yc + side * yt * np.cos(th)))

    return _by_arc_length(surface, 0.0, math.pi, points)


def cam(points: int = DEFAULT_POINTS, base_radius: float = 40.0, lift: float = 12.0) -> np.ndarray:
    """Disc cam: rise 120° (cycloidal), dwell 60°, return 120°, dwell 60°."""

    def cycloid(x: np.ndarray) -> np.ndarray:
        return x - np.sin(2 * math.pi * x) / (2 * math.pi)

    def profile(phi: np.ndarray) -> np.ndarray:
        u = np.degrees(phi)
        lift_of = np.select(
            [u < 120, u < 180, u < 300],
            [cycloid(u / 120), np.ones_like(u), 1 - cycloid((u - 180) / 120)],
            np.zeros_like(u),
        )
        r = base_radius + lift * lift_of
        return np.column_stack((r * np.cos(phi), r * np.sin(phi)))

    return _by_arc_length(profile, 0.0, 2 * math.pi, points)


def epitrochoid(points: int = DEFAULT_POINTS, big_r: float = 60.0, small_r: float = 20.0, d: float = 10.0) -> np.ndarray:
    k = (big_r + small_r) / small_r
    f = lambda t: np.column_stack(  # noqa: E731
        ((big_r + small_r) * np.cos(t) - d * np.cos(k * t), (big_r + small_r) * np.sin(t) - d * np.sin(k * t))
    )
    return _by_arc_length(f, 0.0, 2 * math.pi, points)


def sine(points: int = DEFAULT_POINTS, amplitude: float = 20.0, wavelength: float = 100.0, length: float = 200.0) -> np.ndarray:
    f = lambda t: np.column_stack((t, amplitude * np.sin(2 * math.pi * t / wavelength)))  # noqa: E731
    return _by_arc_length(f, 0.0, length, points)


def clothoid(points: int = DEFAULT_POINTS, length: float = 200.0, end_radius: float = 40.0) -> np.ndarray:
    """Euler spiral from curvature 0 to 1/end_radius over ``length`` (exact, via Fresnel)."""
    from scipy.special import fresnel  # heavy; only the clothoid needs it

    scale = math.sqrt(math.pi * length * end_radius)
    t = np.linspace(0.0, length / scale, points)
    s_int, c_int = fresnel(t)
    return scale * np.column_stack((c_int, s_int))


def _sample_polysegment(poly: Polysegment, points: int) -> np.ndarray:
    xy, _ = poly.sample(poly.length / max(points - 1, 1))
    return xy


def rounded_rectangle(points: int = DEFAULT_POINTS, width: float = 150.0, height: float = 80.0, radius: float = 10.0) -> np.ndarray:
    """Exactly 4 lines + 4 quarter arcs, counter-clockwise from the middle of the bottom edge."""
    if not 0 < radius < min(width, height) / 2:
        raise InputError("builtin:rounded-rectangle: need 0 < radius < min(width, height) / 2")
    lw, lh, q = width - 2 * radius, height - 2 * radius, math.pi / 2 * radius
    k = 1 / radius
    segs = chain((0.0, -height / 2), 0.0, [0, k, 0, k, 0, k, 0, k, 0], [lw / 2, q, lh, q, lw, q, lh, q, lw / 2])
    return _sample_polysegment(Polysegment(segs, closed=True), points)


def polygon(points: int = DEFAULT_POINTS, sides: int = 5, radius: float = 60.0) -> np.ndarray:
    """Regular polygon with sharp corners (every vertex a true corner)."""
    sides = int(sides)
    if sides < 3:
        raise InputError("builtin:polygon: sides must be >= 3")
    ang = np.linspace(0.0, 2 * math.pi, sides + 1) + math.pi / 2
    corners = np.column_stack((radius * np.cos(ang), radius * np.sin(ang)))
    corners[-1] = corners[0]
    lines = tuple(Line(tuple(a), tuple(b)) for a, b in zip(corners[:-1], corners[1:]))
    return _sample_polysegment(Polysegment(lines, closed=True), points)


def d_shape(points: int = DEFAULT_POINTS, radius: float = 50.0, stem: float = 40.0) -> np.ndarray:
    """A glyph 'D': a straight stem, two lines and a half circle; the two stem ends are true
    (90°) corners, the arc joins its lines tangentially."""
    segs = chain((0.0, -radius), 0.0, [0, 1 / radius, 0], [stem, math.pi * radius, stem])
    end = segs[-1].end
    closing = chain(end, -math.pi / 2, [0], [2 * radius])
    return _sample_polysegment(Polysegment(segs + closing, closed=True), points)


def raster(points: int = DEFAULT_POINTS, width: float = 200.0, pitch: float = 20.0, passes: int = 6) -> np.ndarray:
    """Serpentine raster: ``passes`` straight passes joined by semicircular turn-arounds."""
    passes = int(passes)
    if passes < 1 or pitch <= 0 or width <= 0:
        raise InputError("builtin:raster: need passes >= 1, pitch > 0, width > 0")
    kappas, lengths = [], []
    for i in range(passes):
        kappas.append(0.0)
        lengths.append(width)
        if i < passes - 1:
            kappas.append((2.0 if i % 2 == 0 else -2.0) / pitch)
            lengths.append(math.pi * pitch / 2)
    segs = chain((-width / 2, 0.0), 0.0, kappas, lengths)
    return _sample_polysegment(Polysegment(segs), points)


# parameters that are lengths, radii or counts: zero or negative values make no curve
POSITIVE = {
    "points", "width", "turns", "a", "b", "chord", "base_radius", "big_r", "small_r", "wavelength",
    "length", "end_radius", "height", "radius", "sides", "stem", "pitch", "passes",
}

BUILTINS: dict[str, Callable[..., np.ndarray]] = {
    "paper-spiral": paper_spiral,
    "ellipse": ellipse,
    "naca": naca,
    "cam": cam,
    "epitrochoid": epitrochoid,
    "sine": sine,
    "clothoid": clothoid,
    "rounded-rectangle": rounded_rectangle,
    "polygon": polygon,
    "d-shape": d_shape,
    "raster": raster,
}


def builtin_curve(name: str, closed: ClosedMode = "auto", **params: float | int | str) -> Curve:
    """Sample the named built-in curve.

    Args:
        name: a built-in curve (ellipse, paper-spiral, sine, ...; the InputError lists them).
        closed: as make_curve's (``"auto"``: closed when its ends meet within a tiny share of its length).
        **params: its parameters (e.g. ``a``, ``b``, ``turns``, ``points``).

    Returns:
        The sampled Curve.

    Raises:
        InputError: an unknown name or parameter, or a value out of range.
        BudgetExceeded: more points than the curve_points budget.
    """
    if name not in BUILTINS:
        raise InputError(f"builtin:{name}: unknown curve; choose one of {', '.join(sorted(BUILTINS))}")
    func = BUILTINS[name]
    for key, value in params.items():
        if isinstance(value, float) and not math.isfinite(value):
            raise InputError(f"builtin:{name}: parameter {key} must be finite")
        if key in POSITIVE and not (isinstance(value, (int, float)) and value > 0):
            raise InputError(f"builtin:{name}: parameter {key} must be a positive number, got {value!r}")
    if "points" in params and params["points"] < 3:
        raise InputError(f"builtin:{name}: points must be at least 3")
    for key in sorted(INTEGER_PARAMETERS & params.keys()):
        check_budget(f"builtin:{name}: {key}", params[key], "curve_points", f"give fewer {key}")
    try:
        with np.errstate(all="ignore"):  # overflowing parameters give inf/nan, which make_curve rejects
            xy = func(**params)
    except (TypeError, ValueError, ZeroDivisionError, OverflowError) as exc:
        raise InputError(f"builtin:{name}: bad parameter ({exc})") from None
    return make_curve(xy, f"builtin:{name}", closed)


TEXT_PARAMETERS = {"code"}
INTEGER_PARAMETERS = {"points", "sides", "passes"}


def parse_builtin_spec(spec: str, closed: ClosedMode = "auto") -> Curve:
    """``builtin:NAME`` or ``builtin:NAME:key=value,key=value``, closed as ``closed`` says."""
    body = spec[len("builtin:"):]
    name, _, arg_text = body.partition(":")
    params: dict[str, float | int | str] = {}
    for item in filter(None, (a.strip() for a in arg_text.split(","))):
        key, sep, value = item.partition("=")
        if not sep:
            raise InputError(f"{spec}: parameter {item!r} must be key=value")
        key, value = key.strip().replace("-", "_"), value.strip()
        if key in TEXT_PARAMETERS:
            params[key] = value
            continue
        try:
            number = float(value)
        except ValueError:
            raise InputError(f"{spec}: parameter {key} must be a number, got {value!r}") from None
        if key in INTEGER_PARAMETERS:
            if not number.is_integer():
                raise InputError(f"{spec}: parameter {key} must be a whole number, got {value!r}")
            params[key] = int(number)
        else:
            params[key] = number
    return builtin_curve(name.strip(), closed, **params)
