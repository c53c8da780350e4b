"""Numbers in text tables read as people write them, or refused: never misread without a word."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.core import number_text
from coatsim.core.number_text import read_rows
from coatsim.geometry.curves import read_points_file

RECT = [(0.0, 0.0), (100.5, 0.0), (100.5, 50.25), (0.0, 50.25), (0.0, 0.0)]


def _comma(x: float) -> str:
    return f"{x:g}".replace(".", ",")


@pytest.mark.parametrize("sep", ["\t", " ", ";", "  ", " ; "])
def test_decimal_commas_with_any_separator_are_read_as_decimals(tmp_path, sep):
    path = tmp_path / "eu.csv"
    path.write_text("".join(f"{_comma(x)}{sep}{_comma(y)}\n" for x, y in RECT), encoding="utf-8")
    with pytest.warns(CoatsimWarning, match="decimal mark"):
        points = read_points_file(path)
    assert np.array_equal(points, np.array(RECT))


@pytest.mark.parametrize("minus", ["\u2212", "\u2013", "\uff0d"])
def test_a_unicode_minus_in_the_first_row_is_a_number_not_a_header(tmp_path, minus):
    path = tmp_path / "minus.csv"
    rows = [(-5.0, 0.0), (5.0, 0.0), (5.0, 5.0), (-5.0, 0.0)]
    path.write_text("".join(f"{x:g},{y:g}\n".replace("-", minus) for x, y in rows), encoding="utf-8")
    with pytest.warns(CoatsimWarning, match="minus sign"):
        points = read_points_file(path)
    assert np.array_equal(points, np.array(rows))  # the closed curve stays closed: its first row is kept


def test_a_header_is_a_first_row_without_any_number():
    rows = read_rows("x;y\n1;2\n", "t.csv", "x,y")
    assert rows.header == ["x", "y"] and rows.values == [[1.0, 2.0]]
    with pytest.raises(InputError, match=r"t.csv:1: field 1 is not a number"):
        read_rows("x1,2\n1,2\n", "t.csv", "x,y")


@pytest.mark.parametrize("text, fragment", [
    ("1,5;2,5\n1.5;2.5\n", "decimal commas (line 1) and decimal points (line 2)"),
    ("1_000,2\n", "field 1 is not a number"),
    ("0x10,2\n", "field 1 is not a number"),
    ("1.2.3,2\n", "field 1 is not a number"),
    ("2mm,2\n", "field 1 is not a number"),
    ("1,nan\n", "not finite"),
])
def test_forms_that_are_not_numbers_are_refused_with_line_and_field(text, fragment):
    with pytest.raises(InputError, match=re.escape(fragment)):
        read_rows(text, "t.csv", "x,y")


def test_three_columns_are_a_3d_curve_never_cut_to_two(tmp_path):
    path = tmp_path / "xyz.csv"
    t = np.linspace(0, 4 * np.pi, 50)
    helix = np.c_[np.cos(t), np.sin(t), t]
    np.savetxt(path, helix, delimiter=",")
    assert read_points_file(path).shape == (50, 3)
    np.save(tmp_path / "xyz.npy", helix)
    assert read_points_file(tmp_path / "xyz.npy").shape == (50, 3)


@pytest.mark.parametrize("columns", [4, 5])
def test_more_than_three_columns_are_refused(tmp_path, columns):
    path = tmp_path / "wide.csv"
    np.savetxt(path, np.ones((5, columns)) * np.arange(5)[:, None], delimiter=",")
    with pytest.raises(InputError, match=f"{columns} numeric columns"):
        read_points_file(path)
    np.save(tmp_path / "wide.npy", np.ones((5, columns)))
    with pytest.raises(InputError, match=r"\(n, 2\) or \(n, 3\)"):
        read_points_file(tmp_path / "wide.npy")


finite = st.floats(-1e6, 1e6, allow_nan=False).map(lambda v: round(v, 6))


@settings(max_examples=150, deadline=None)
@given(st.lists(st.tuples(finite, finite), min_size=1, max_size=20),
       st.sampled_from([",", ";", "\t", " "]), st.booleans(), st.booleans())
def test_any_table_reads_back_exactly_or_is_refused(points, sep, comma, unicode_minus):
    """Written with any separator, decimal mark and minus sign, a table reads back to the same
    numbers (a decimal comma cannot share the comma separator: that one is written with points)."""
    comma = comma and sep != ","
    def fmt(v: float) -> str:
        text = repr(float(v))
        text = text.replace(".", ",") if comma else text
        return text.replace("-", "\u2212") if unicode_minus else text
    text = "".join(sep.join(fmt(v) for v in row) + "\n" for row in points)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rows = read_rows(text, "t.csv", "x,y")
    assert rows.values == [list(map(float, row)) for row in points]


def _line_by_line(text: str):
    """What the line-by-line reader alone makes of a text: its rows or its error."""
    fast = number_text._fast_chunk
    number_text._fast_chunk = lambda *args: False
    try:
        return _outcome(text)
    finally:
        number_text._fast_chunk = fast


def _outcome(text: str):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            rows = read_rows(text, "t.csv", "x,y")
        except InputError as exc:
            return str(exc)
    return rows.values, rows.lines.tolist(), rows.header, sorted(rows.notes)


TOKENS = ["1", "-2.5", "1,5", "+3e2", "2.", ".5", "1e", ".", "", "x", "nan", "1.2.3", "\u22124", "1\u00a0000",
          "\u0663", "#c", '"7"', "1_0", "0", "1e400", "5,", "-", "12,25", "E5", "3E-2"]


@settings(max_examples=400, deadline=None)
@given(st.lists(st.tuples(st.lists(st.sampled_from(TOKENS), min_size=0, max_size=4),
                          st.sampled_from([",", ";", "\t", " ", "  ", " , ", ", ", " ;", "\t "]),
                          st.sampled_from(["", ",", ";", "\t", " "]), st.sampled_from(["\n", "\r\n", "\r", "\n\n"])),
                min_size=1, max_size=6), st.booleans(), st.sampled_from([4, 16, 1 << 20]))
def test_the_numpy_reader_agrees_with_the_line_by_line_reader(lines, same, chunk):
    """Every table, however odd, reads the same (numbers, line numbers, header, notes, error) by
    chunks at numpy speed as line by line."""
    if same:  # most real files repeat one separator on every line
        lines = [(fields, lines[0][1], lines[0][2], end) for fields, _, _, end in lines]
    text = "".join(sep.join(fields) + trail + end for fields, sep, trail, end in lines)
    default, number_text.CHUNK_CHARS = number_text.CHUNK_CHARS, chunk  # chunks of a few lines too
    try:
        assert _outcome(text) == _line_by_line(text)
    finally:
        number_text.CHUNK_CHARS = default


@pytest.mark.parametrize("text", [
    "x,y\n" + "1.5,2.5\n" * 50, "1,5;2,5\n" * 50, "1,5\t2,5\r\n" * 50, "1.5, 2.5\n" * 50, "1,5 2,5\n" * 30,
    "\u22121,5;2\n" * 40, "# c\n1 2\n\n3 4 # d\n" * 40, "1;2;\n" * 40, "1,2\n" * 40, "1 2\n" * 40,
])
def test_plain_tables_are_read_at_numpy_speed_and_agree(text, monkeypatch):
    """These tables are read by the numpy reader (no chunk falls back) to the same result."""
    calls = []
    fast = number_text._fast_chunk
    with monkeypatch.context() as patch:
        patch.setattr(number_text, "_fast_chunk", lambda *args: calls.append(fast(*args)) or calls[-1])
        got = _outcome(text)
    assert calls and all(calls)
    assert got == _line_by_line(text)


@pytest.mark.parametrize("codec", ["utf-16", "utf-32", "utf-8-sig"])
def test_a_table_with_a_byte_order_mark_is_read_in_its_encoding(tmp_path, codec):
    """Spreadsheets save "Unicode text" as UTF-16 with a byte-order mark: read as written."""
    path = tmp_path / "u.txt"
    text = "x\ty\r\n" + "".join(f"{x:g}\t{y:g}\r\n" for x, y in RECT)
    path.write_bytes(text.encode(codec))  # each of these codecs writes its byte-order mark first
    assert np.array_equal(read_points_file(path), np.array(RECT))


def test_utf16_without_a_byte_order_mark_is_refused(tmp_path):
    """Without the mark its NUL bytes are read as UTF-8 characters: fields that are not numbers."""
    path = tmp_path / "u.csv"
    path.write_bytes("0,0\n1,1\n".encode("utf-16-le"))
    with pytest.raises(InputError, match="is not a number"):
        read_points_file(path)
