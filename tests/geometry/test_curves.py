"""Curve input: CSV/TXT/NPY reading, closure detection and forcing, duplicate points, every
bad input as an InputError naming the file (and line), and the built-in curves."""

from __future__ import annotations

import math
import warnings
from contextlib import contextmanager

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.geometry import BUILTINS, builtin_curve, load_curve, make_curve, read_curve_file, segment_curve
from coatsim.geometry.curves import ends_meet
from coatsim.geometry.space.curve import make_space_curve

# Six points of a parabola, written with repr() so every reader must give them back exactly.
POINTS = np.array([[0.0, 0.0], [1.5, 0.25], [3.0, 1.0], [4.5, 2.25], [6.0, 4.0], [7.25, 6.125], [-2.5e-3, 1e3]])


def write_rows(path, rows, sep=",", header=None, newline="\n"):
    lines = ([header] if header is not None else []) + [sep.join(repr(float(v)) for v in row) for row in rows]
    path.write_text(newline.join(lines) + newline, encoding="utf-8")
    return path


def circle(n: int = 40, radius: float = 30.0) -> np.ndarray:
    a = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    return np.column_stack((radius * np.cos(a), radius * np.sin(a)))


@contextmanager
def raises_naming(where: str, *fragments: str):
    """An InputError whose one-line message contains ``where`` and every fragment."""
    with pytest.raises(InputError) as info:
        yield info
    msg = str(info.value)
    assert where in msg, f"message does not name {where!r}: {msg}"
    for f in fragments:
        assert f in msg, f"message lacks {f!r}: {msg}"
    assert "\n" not in msg, "message must be one line"


# ---------------------------------------------------------------- reading


@pytest.mark.parametrize("sep", [",", ", ", " ", "   ", "\t", ";", "; "], ids=repr)
@pytest.mark.parametrize("header", [False, True])
@pytest.mark.parametrize("suffix", [".csv", ".txt"])
def test_text_separators_and_header(tmp_path, sep, header, suffix):
    head = sep.join(["x", "y"]) if header else None
    path = write_rows(tmp_path / f"c{suffix}", POINTS, sep, head)
    c = read_curve_file(path)
    np.testing.assert_array_equal(c.points, POINTS)
    assert c.closed is False and c.name == str(path)


def test_comments_blank_lines_crlf_and_bom(tmp_path):
    body = "\ufeff# exported by a CAD tool\r\n\"x\",\"y\"\r\n\r\n"
    for k, (x, y) in enumerate(POINTS.tolist()):
        body += f"{x!r},{y!r}" + ("   # a trailing note\r\n" if k % 2 else "\r\n")
        if k == 3:
            body += "   # an indented comment line\r\n\t\r\n"
    path = tmp_path / "commented.csv"
    path.write_bytes(body.encode("utf-8"))
    np.testing.assert_array_equal(read_curve_file(path).points, POINTS)


def test_quoted_header_and_extra_whitespace(tmp_path):
    path = tmp_path / "q.txt"
    path.write_text("  'x'\t'y'  \n" + "\n".join(f"  {x!r}\t {y!r}  " for x, y in POINTS.tolist()) + "\n")
    np.testing.assert_array_equal(read_curve_file(path).points, POINTS)


@pytest.mark.parametrize("dtype", [np.float64, np.float32, np.int64])
def test_npy(tmp_path, dtype):
    data = (POINTS * 8).astype(dtype)
    path = tmp_path / "c.npy"
    np.save(path, data)
    c = load_curve(str(path))
    np.testing.assert_array_equal(c.points, data.astype(float))
    assert c.points.dtype == np.float64 and c.name == str(path)


def test_load_curve_reads_files_and_builtins(tmp_path):
    path = write_rows(tmp_path / "p.csv", POINTS)
    np.testing.assert_array_equal(load_curve(str(path)).points, POINTS)
    assert load_curve("builtin:ellipse:a=120,b=40,points=500").points[:, 0].max() == pytest.approx(120.0)


# ---------------------------------------------------------------- closure


def test_first_equal_last_is_closed(tmp_path):
    pts = np.vstack((circle(), circle()[:1]))
    c = read_curve_file(write_rows(tmp_path / "c.csv", pts))
    assert c.closed is True
    assert len(c.points) == len(pts)
    np.testing.assert_array_equal(c.points, pts)


def test_nearly_closed_within_tiny_fraction_snaps_onto_the_first_point(tmp_path):
    pts = np.vstack((circle(), circle()[:1]))
    length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    pts[-1] += [0.5e-4 * length, 0.2e-4 * length]  # gap ~5e-5 of the length
    with pytest.warns(CoatsimWarning, match=r"read as closed, its ends 0.0\d+ mm apart .* moved onto the first"):
        c = read_curve_file(write_rows(tmp_path / "c.csv", pts))  # it moves more than 0.01 mm: said
    assert c.closed is True and len(c.points) == len(pts)
    assert tuple(c.points[-1]) == tuple(c.points[0])
    np.testing.assert_array_equal(c.points[:-1], pts[:-1])


def test_a_long_curve_closed_by_its_length_says_how_far_its_last_point_moved():
    with pytest.warns(CoatsimWarning, match="its ends 200 mm apart"):  # 2 waves of 1 km amplitude: 8 km long
        c = load_curve("builtin:sine:amplitude=1e6", "auto")
    assert c.closed
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        kept_open = load_curve("builtin:sine:amplitude=1e6", "no")
    assert not kept_open.closed and kept_open.points[-1][0] == pytest.approx(200.0)  # its own last point


def test_a_visible_gap_is_open(tmp_path):
    pts = np.vstack((circle(), circle()[:1]))
    length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    pts[-1] += [5e-3 * length, 0.0]
    c = read_curve_file(write_rows(tmp_path / "c.csv", pts))
    assert c.closed is False
    np.testing.assert_array_equal(c.points, pts)


def test_closed_forcing(tmp_path):
    three_quarters = circle()[:30]
    open_path = write_rows(tmp_path / "open.csv", three_quarters)
    assert read_curve_file(open_path).closed is False
    forced = load_curve(str(open_path), "yes")
    assert forced.closed is True
    assert len(forced.points) == len(three_quarters) + 1 and tuple(forced.points[-1]) == tuple(forced.points[0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert load_curve(str(write_rows(tmp_path / "loop.csv", circle())), "no").closed is False

    closed_path = write_rows(tmp_path / "closed.csv", np.vstack((circle(), circle()[:1])))
    kept_open = load_curve(str(closed_path), "no")
    assert kept_open.closed is False and len(kept_open.points) == len(circle()) + 1
    assert load_curve(str(closed_path), "auto").closed is True


def _placed(points: np.ndarray, dim: int, seed: int) -> np.ndarray:
    """Points in the plane, in 3-D turned into a random plane and moved."""
    if dim == 2:
        return points
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return np.column_stack((points, np.zeros(len(points)))) @ q.T + rng.uniform(-100, 100, 3)


@settings(max_examples=40, deadline=None)
@given(n=st.integers(8, 400), radius=st.floats(1.0, 500.0), start=st.floats(0.0, 2 * math.pi),
       dim=st.sampled_from([2, 3]), seed=st.integers(0, 2**16))
def test_a_loop_given_without_its_closing_point_is_closed_and_says_so(n, radius, start, dim, seed):
    a = start + np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    pts = _placed(np.column_stack((radius * np.cos(a), radius * np.sin(a))), dim, seed)
    make = make_curve if dim == 2 else make_space_curve
    with pytest.warns(CoatsimWarning, match=r"c.csv: read as closed, its ends [0-9.e+-]+ mm apart, about one point spacing"):
        c = make(pts, "c.csv", "auto")
    assert c.closed and len(c.points) == n + 1
    np.testing.assert_array_equal(c.points[:-1], pts)
    assert tuple(c.points[-1]) == tuple(c.points[0])


@settings(max_examples=40, deadline=None)
@given(n=st.integers(12, 400), missing=st.floats(2.0, 40.0), dim=st.sampled_from([2, 3]), seed=st.integers(0, 2**16))
def test_an_arc_stopping_more_than_a_step_and_a_half_short_of_closing_is_open(n, missing, dim, seed):
    step = 2 * math.pi / (n - 1 + missing)  # the gap spans `missing` steps of the arc
    a = step * np.arange(n)
    pts = _placed(np.column_stack((40 * np.cos(a), 40 * np.sin(a))), dim, seed)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        c = (make_curve if dim == 2 else make_space_curve)(pts, "c.csv", "auto")
    assert not c.closed and len(c.points) == n


def test_a_rectangle_from_a_corner_without_its_closing_point_is_closed():
    """The gap runs on along the last side; the start is a corner, which one end may be."""
    side = np.linspace(0.0, 1.0, 21)[:-1]
    corners = np.array([[0.0, 0.0], [80.0, 0.0], [80.0, 30.0], [0.0, 30.0], [0.0, 0.0]])
    pts = np.vstack([a + np.outer(side, b - a) for a, b in zip(corners[:-1], corners[1:])])
    with pytest.warns(CoatsimWarning, match="about one point spacing"):
        assert make_curve(pts, "r.csv", "auto").closed


def test_a_path_that_comes_back_along_itself_is_not_closed_by_its_last_step():
    out = np.column_stack((np.linspace(0.0, 100.0, 51), np.zeros(51)))
    back = out[::-1][1:-1]  # back along the same line, stopping one step short of the start
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert make_curve(np.vstack((out, back)), "hairpin.csv", "auto").closed is False


def test_a_circle_given_without_its_closing_point_is_one_circle():
    with pytest.warns(CoatsimWarning, match="about one point spacing"):
        curve = make_curve(circle(200, 40.0), "c.csv", "auto")
    poly = segment_curve(curve, 0.1).polysegment
    assert poly.closed and poly.n_segments == 1 and poly.segments[0].radius == pytest.approx(40.0, abs=0.1)


def test_a_programs_path_is_closed_only_where_it_returns_to_its_start():
    """A program drives no step it does not list: ends_meet, not a step's gap, closes its path."""
    assert not ends_meet(circle(200, 40.0))
    assert ends_meet(np.vstack((circle(200, 40.0), circle(200, 40.0)[:1])))
    nearly = np.vstack((circle(200, 40.0), circle(200, 40.0)[:1] + [0.0, 0.02]))  # 8e-5 of the length
    assert ends_meet(nearly)


def test_closed_forcing_on_builtins():
    assert load_curve("builtin:sine:points=300").closed is False
    forced = load_curve("builtin:sine:points=300", "yes")
    assert forced.closed is True and tuple(forced.points[-1]) == tuple(forced.points[0])
    assert load_curve("builtin:ellipse:points=300").closed is True
    assert load_curve("builtin:ellipse:points=300", "no").closed is False


def test_forcing_closed_needs_three_distinct_points():
    with raises_naming("two.csv", "three"):
        make_curve(np.array([[0.0, 0.0], [1.0, 0.0]]), "two.csv", "yes")


# ---------------------------------------------------------------- duplicates


def test_consecutive_duplicates_dropped_silently(tmp_path):
    rows = [POINTS[0], POINTS[0], POINTS[1], POINTS[2], POINTS[2], POINTS[2], POINTS[3], POINTS[1], POINTS[4]]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        c = read_curve_file(write_rows(tmp_path / "d.csv", rows))
    # Only consecutive repeats go; a point visited again later stays.
    np.testing.assert_array_equal(c.points, np.array([POINTS[i] for i in (0, 1, 2, 3, 1, 4)]))


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.integers(-50, 50), st.integers(-50, 50)), min_size=2, max_size=30),
    st.lists(st.integers(1, 4), min_size=30, max_size=30),
)
def test_dedup_matches_reference(raw, repeats):
    pts = np.array(raw, dtype=float)
    expanded = np.repeat(pts, repeats[: len(pts)], axis=0)
    keep = np.ones(len(pts), bool)
    keep[1:] = np.any(pts[1:] != pts[:-1], axis=1)
    expected = pts[keep]
    if len(expected) < 2:
        with pytest.raises(InputError):
            make_curve(expanded, "h.csv", "no")
        return
    c = make_curve(expanded, "h.csv", "no")
    np.testing.assert_array_equal(c.points, expected)
    assert not np.any(np.all(np.diff(c.points, axis=0) == 0, axis=1))


# ---------------------------------------------------------------- bad files


BAD_TEXT = {
    "empty": ("", None, ()),
    "blank lines only": ("\n\n   \n", None, ()),
    "header only": ("x,y\n", None, ()),
    "comments only": ("# nothing here\n# really\n", None, ()),
    "one point": ("1.0,2.0\n", None, ("one point",)),
    "one point repeated": ("1.0,2.0\n1.0,2.0\n1.0,2.0\n", None, ("equal",)),
    "nan": ("0,0\n1,1\nnan,2\n3,3\n", 3, ()),
    "inf": ("0,0\n1,inf\n2,2\n", 2, ()),
    "negative inf": ("0,0\n1,1\n2,2\n3,-inf\n", 4, ()),
    "text in a numeric column": ("0,0\n1,1\n2,2\n3,abc\n", 4, ("field 2 is not a number",)),
    "text in the x column": ("0;0\n1;1\n2mm;2\n", 3, ("2mm",)),
    "header after data": ("0,0\nx,y\n1,1\n", 2, ()),
    "one column": ("0,0\n1\n2,2\n", 2, ()),
}


@pytest.mark.parametrize("content,line,fragments", BAD_TEXT.values(), ids=list(BAD_TEXT))
def test_bad_text_files(tmp_path, content, line, fragments):
    path = tmp_path / "bad.csv"
    path.write_text(content, encoding="utf-8")
    where = f"{path}:{line}:" if line else str(path)
    with raises_naming(where, *fragments):
        read_curve_file(path)
    with raises_naming(where, *fragments):
        load_curve(str(path))


def test_binary_file_named_csv(tmp_path):
    path = tmp_path / "garbage.csv"
    path.write_bytes(bytes(range(256)) * 4)
    with raises_naming(str(path)):
        read_curve_file(path)


@pytest.mark.parametrize(
    "data",
    [
        np.array([[0.0, 0.0], [np.nan, 1.0], [2.0, 2.0]]),
        np.array([[0.0, 0.0], [1.0, np.inf], [2.0, 2.0]]),
        np.zeros((0, 2)),
        np.array([[1.0, 2.0]]),
        np.ones((5, 2)),
        np.arange(10.0),
        np.array([["a", "b"], ["c", "d"]]),
    ],
    ids=["nan", "inf", "empty", "one point", "all equal", "1-d", "strings"],
)
def test_bad_npy(tmp_path, data):
    path = tmp_path / "bad.npy"
    np.save(path, data)
    with raises_naming(str(path)):
        read_curve_file(path)


def test_npy_that_is_not_npy(tmp_path):
    path = tmp_path / "fake.npy"
    path.write_text("0,0\n1,1\n")
    with raises_naming(str(path)):
        read_curve_file(path)


def test_unreadable_paths(tmp_path):
    missing = tmp_path / "nowhere" / "missing.csv"
    with raises_naming(str(missing)):
        load_curve(str(missing))
    with raises_naming(str(tmp_path)):
        load_curve(str(tmp_path))
    folder_npy = tmp_path / "folder.npy"
    folder_npy.mkdir()
    with raises_naming(str(folder_npy)):
        read_curve_file(folder_npy)


def test_nan_names_the_point_in_arrays():
    with raises_naming("arr", "3"):
        make_curve(np.array([[0.0, 0.0], [1.0, 1.0], [np.nan, 2.0]]), "arr")


# ---------------------------------------------------------------- bad built-ins


def test_unknown_builtin_lists_the_choices():
    with raises_naming("builtin:hexagon", "ellipse", "paper-spiral"):
        load_curve("builtin:hexagon")


BAD_BUILTINS = [
    "builtin:ellipse:foo=1",
    "builtin:ellipse:a",
    "builtin:ellipse:a=abc",
    "builtin:ellipse:points=1",
    "builtin:ellipse:points=0",
    "builtin:ellipse:a=0,b=0",
    "builtin:ellipse:a=nan",
    "builtin:sine:wavelength=0",
    "builtin:polygon:sides=2",
    "builtin:raster:passes=0",
    "builtin:raster:pitch=0",
    "builtin:rounded-rectangle:radius=0",
    "builtin:rounded-rectangle:radius=50",
    "builtin:rounded-rectangle:radius=abc",
    "builtin:naca:code=abcd",
    "builtin:paper-spiral:width=0",
]

# Each of these once escaped as ValueError / ZeroDivisionError instead of an InputError.
BAD_BUILTINS += [
    "builtin:polygon:sides=abc",
    "builtin:raster:passes=x",
    "builtin:ellipse:points=-3",
    "builtin:paper-spiral:points=0",
    "builtin:clothoid:end_radius=-1",
    "builtin:clothoid:length=0",
    "builtin:d-shape:radius=0",
    "builtin:polygon:radius=0",
    "builtin:epitrochoid:small_r=0",
]


@pytest.mark.parametrize("spec", BAD_BUILTINS)
def test_bad_builtin_parameter_is_an_input_error(spec):
    name = spec.split(":")[1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        with raises_naming(f"builtin:{name}"):
            load_curve(spec)


def test_naca_code_from_a_spec_string():
    """Regression: the spec parser once turned code=2412 into 2412.0, which naca() rejected."""
    c = load_curve("builtin:naca:code=2412,points=800")
    assert c.closed and c.points[:, 1].max() > -c.points[:, 1].min() + 1.0  # cambered: upper side higher
    np.testing.assert_array_equal(load_curve("builtin:naca:code=0012,points=800").points,
                                  builtin_curve("naca", code="0012", points=800).points)


def test_naca_code_keyword_works():
    c = builtin_curve("naca", code="2412", points=800)
    sym = builtin_curve("naca", code="0012", points=800)
    assert abs(sym.points[:, 1].max() + sym.points[:, 1].min()) < 1e-9
    assert c.points[:, 1].max() > -c.points[:, 1].min() + 1.0


# ---------------------------------------------------------------- built-in curves

EXPECTED_CLOSED = {
    "paper-spiral": False, "ellipse": True, "naca": True, "cam": True, "epitrochoid": True, "sine": False,
    "clothoid": False, "rounded-rectangle": True, "polygon": True, "d-shape": True, "raster": False,
}
EXACT_PRIMITIVE = {"rounded-rectangle", "polygon", "d-shape", "raster"}


def test_the_builtin_list_is_the_documented_one():
    assert set(BUILTINS) == set(EXPECTED_CLOSED)


@pytest.mark.parametrize("name", sorted(BUILTINS))
def test_builtin_loads_uniformly_sampled(name):
    c = load_curve(f"builtin:{name}")
    assert c.name == f"builtin:{name}"
    assert c.closed is EXPECTED_CLOSED[name]
    assert np.isfinite(c.points).all()
    if c.closed:
        assert tuple(c.points[-1]) == tuple(c.points[0])
    edges = np.linalg.norm(np.diff(c.points, axis=0), axis=1)
    assert edges.min() > 0
    step = c.length / (3000 - 1)
    if name in EXACT_PRIMITIVE:
        # Every segment is cut into equal pieces no longer than the nominal step.
        assert 3000 <= len(c.points) <= 3000 + 12
        assert edges.max() <= step * (1 + 1e-9)
        assert edges.min() >= 0.98 * step
    else:
        assert len(c.points) == 3000
        med = np.median(edges)
        assert np.abs(edges - med).max() <= 1e-3 * med
        assert med == pytest.approx(step, rel=1e-3)


@pytest.mark.parametrize("points", [200, 1234])
def test_builtin_point_count_parameter(points):
    assert len(load_curve(f"builtin:ellipse:points={points}").points) == points
    assert len(builtin_curve("sine", points=points).points) == points


SEGMENT_ENDS = {
    "rounded-rectangle": [(0, -40), (65, -40), (75, -30), (75, 30), (65, 40), (-65, 40), (-75, 30), (-75, -30), (-65, -40)],
    "polygon": [(60 * math.cos(a), 60 * math.sin(a)) for a in math.pi / 2 + 2 * math.pi * np.arange(5) / 5],
    "d-shape": [(0, -50), (40, -50), (40, 50), (0, 50)],
    "raster": [(x, 20 * k) for k in range(6) for x in (-100, 100)],
}


@pytest.mark.parametrize("name", sorted(SEGMENT_ENDS))
def test_exact_primitive_shapes_include_their_segment_ends(name):
    pts = load_curve(f"builtin:{name}").points
    for p in SEGMENT_ENDS[name]:
        assert np.linalg.norm(pts - np.asarray(p, float), axis=1).min() < 1e-9, p


@pytest.mark.parametrize("name", ["paper-spiral", "ellipse", "sine", "clothoid", "epitrochoid", "cam", "naca"])
def test_builtin_samples_lie_on_the_curve(name):
    """Spot-check the samples against the defining equation (not just the sampling)."""
    p = load_curve(f"builtin:{name}:points=2000").points
    x, y = p[:, 0], p[:, 1]
    if name == "ellipse":
        assert np.abs((x / 100) ** 2 + (y / 50) ** 2 - 1).max() < 1e-6
    elif name == "sine":
        assert np.abs(y - 20 * np.sin(2 * np.pi * x / 100)).max() < 1e-3
        assert x[0] == 0 and x[-1] == pytest.approx(200)
    elif name == "clothoid":
        # curvature grows linearly from 0 to 1/40 over 200 mm
        d = np.diff(p, axis=0)
        h = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
        assert h[-1] - h[0] == pytest.approx(200 / (2 * 40), rel=1e-3)
    elif name == "paper-spiral":
        assert np.ptp(x) == pytest.approx(200.0)
    elif name == "epitrochoid":
        r = np.hypot(x, y)
        assert r.max() == pytest.approx(90.0, abs=1e-3) and r.min() == pytest.approx(70.0, abs=1e-2)
    elif name == "cam":
        r = np.hypot(x, y)
        assert r.max() == pytest.approx(52.0, abs=1e-3) and r.min() == pytest.approx(40.0, abs=1e-6)
    elif name == "naca":
        assert x.max() == pytest.approx(200.0, abs=1e-9) and x.min() == pytest.approx(0.0, abs=1e-2)
        assert np.ptp(y) == pytest.approx(0.12 * 200, rel=2e-3)


# ---------------------------------------------------------------- regressions


def test_decimal_comma_rows_are_not_misread(tmp_path):
    """A decimal-comma file ('1,5;2,5') was once read as (1, 5) without any error."""
    path = tmp_path / "eu.csv"
    path.write_text("0;0\n1,5;2,5\n3;4\n")
    try:
        c = read_curve_file(path)
    except InputError as exc:
        assert f"{path}:2" in str(exc)
        return
    assert tuple(c.points[1]) == (1.5, 2.5)


@pytest.mark.parametrize("header", ["x (mm),y (mm)", "X [mm];Y [mm]", "x_mm\ty_mm"])
def test_header_with_units(tmp_path, header):
    """A header naming units was once reported as 'not a number: (mm)'."""
    sep = ";" if ";" in header else ("\t" if "\t" in header else ",")
    path = write_rows(tmp_path / "units.csv", POINTS, sep, header)
    np.testing.assert_array_equal(read_curve_file(path).points, POINTS)


def test_rows_with_more_than_two_columns_are_rejected_or_read_consistently(tmp_path):
    path = tmp_path / "xyz.csv"
    path.write_text("0,0,0\n1,1,5\n2,4,9\n")
    try:
        c = read_curve_file(path)
    except InputError as exc:
        assert str(path) in str(exc)
        return
    np.testing.assert_array_equal(c.points, [[0, 0], [1, 1], [2, 4]])


def test_a_curve_a_few_tolerances_across_gets_a_note_on_its_unit():
    """An ellipse given in metres (0.3 x 0.12) is fitted as a 0.3 mm curve: the result says so."""
    from coatsim.geometry import make_curve, segment_curve

    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    small = np.column_stack((0.15 * np.cos(t), 0.06 * np.sin(t)))
    notes = segment_curve(make_curve(small, "metres", "yes"), 0.1).notes
    assert any("the curve spans 0.323 mm" in n and "read as mm" in n for n in notes), notes
    assert not any("read as mm" in n for n in segment_curve(make_curve(small * 1000, "mm", "yes"), 0.1).notes)


# --- columns named in a header: picked by name, in the header's unit -------------------------

from coatsim.geometry.curves import read_points_file  # noqa: E402

_XYZ = np.array([[0.0, 1.0, 2.0], [3.5, -4.25, 5.0], [6.0, 7.0, -8.5], [9.0, 10.0, 11.0]])


@pytest.mark.parametrize("header, scale", [("x,y,z", 1.0), ("x [mm],y [mm],z [mm]", 1.0), ("X_in,Y_in,Z_in", 25.4),
                                           ("x (cm), y (cm), z (cm)", 10.0), ("x_m,y_m,z_m", 1000.0),
                                           ('x",y",z"', 25.4), ('"x","y","z"', 1.0), ("x inch,y inch,z inch", 25.4)])
def test_a_header_gives_the_unit(tmp_path, header, scale):
    """A header's unit converts the coordinates to mm, and says so; mm or none reads as is."""
    path = tmp_path / "c.csv"
    np.savetxt(path, _XYZ, delimiter=",", header=header, comments="")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert np.allclose(read_points_file(path), _XYZ * scale)
    said = [str(w.message) for w in caught if issubclass(w.category, CoatsimWarning)]
    assert any("converted to mm" in s for s in said) is (scale != 1.0)


@settings(max_examples=40, deadline=None)
@given(order=st.permutations(["x", "y", "z", "i", "t_s"]), three=st.booleans())
def test_named_columns_are_picked_in_any_order(tmp_path_factory, order, three):
    """x, y (and z) among other columns in any order: the points are those columns, x, y, z."""
    names = [n for n in order if three or n != "z"]
    values = {"x": _XYZ[:, 0], "y": _XYZ[:, 1], "z": _XYZ[:, 2], "i": np.arange(4.0), "t_s": np.arange(4.0) / 10}
    path = tmp_path_factory.mktemp("named") / "c.csv"
    np.savetxt(path, np.column_stack([values[n] for n in names]), delimiter=",", header=",".join(names), comments="")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        points = read_points_file(path)
    assert np.array_equal(points, _XYZ if three else _XYZ[:, :2])


@pytest.mark.parametrize("text, message", [
    ("x [ft],y [ft]\n1,2\n3,4\n", r"column 'x \[ft\]': a unit not read"),
    ("x_mm,y_in\n1,2\n3,4\n", r"different units \(in, mm\)"),
    ("i,x,y,z\n0,1,2,3\n1,4,5\n", r"c.csv:3: 3 values where the header names 4 columns"),
])
def test_a_header_that_cannot_be_read_as_it_says_is_refused(tmp_path, text, message):
    path = tmp_path / "c.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=message):
        read_points_file(path)


def test_a_header_naming_no_coordinates_reads_the_columns_in_order(tmp_path):
    """A header of other names (a, b, c) leaves the columns x, y, z in order, as before."""
    path = tmp_path / "c.csv"
    np.savetxt(path, _XYZ, delimiter=",", header="a,b,c", comments="")
    assert np.array_equal(read_points_file(path), _XYZ)
