"""Long expressions and deep calls: a flat run of operators is no deep tree (``x = 1+1+...+1`` of
600 terms parses and evaluates, and so does everything that walks the tree: check-program, the
printer), deep nesting is one line naming the depth budget, and a CALL cycle is named."""

from __future__ import annotations

import operator
import re
from functools import reduce

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.core.errors import ExecutionError
from coatsim.languages.kawasaki_as import ast, parse_as
from coatsim.languages.kawasaki_as.expressions import MAX_DEPTH
from coatsim.languages.kawasaki_as.interpreter import Interpreter
from coatsim.languages.kawasaki_as.printer import expr_text
from coatsim.languages.kawasaki_as.source import AsSyntaxError

from styles import STYLES, run_text, styled


def value_of(expression: str, kind: str = "real"):
    target = "x" if kind == "real" else "$x"
    f = parse_as(f".PROGRAM t()\n  {target} = {expression}\n.END\n.TRANS\np 1 2 3 0 0 0\nq 10 0 0 0 0 0\n.END\n",
                 "f.as")
    run = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    run.run(f.programs[0])
    return run.globals.get(kind, target)


@pytest.mark.parametrize("terms", [600, 5000])
def test_a_long_flat_sum_parses_and_evaluates(terms):
    assert value_of("+".join(["1"] * terms)) == terms
    assert value_of(" - ".join(["1"] * terms)) == 2 - terms
    assert value_of(" AND ".join(["1"] * terms)) == -1.0 and value_of(" OR ".join(["0"] * terms)) == 0.0
    assert value_of(" + ".join(['"ab"'] * terms), "string") == "ab" * terms


@pytest.mark.parametrize("style", STYLES)
def test_check_program_reads_a_program_with_a_600_term_expression(style, tmp_path):
    from program_helpers import check_as as check_program

    body = (".s = " + " + ".join(f"rc[{i % 40}]" for i in range(600)) + "\nIF .s <> " + "+".join(["0"] * 600)
            + ' THEN\nTYPE "differs"\nEND\nJMOVE k\nBREAK\nSIGNAL 1\nLMOVE SHIFT(k BY 80, 0, 0)\nBREAK\n'
            'SIGNAL -1')
    path = tmp_path / "long.as"
    path.write_bytes(styled(body, style, ".TRANS\nk 620 0 300 0 180 0\n.END\n").encode())
    done = check_program(path)
    assert done.n_linear_moves == 1 and done.spray_length_mm == pytest.approx(80.0)
    assert [u.split(": ", 1)[1].split(" ")[0].lower() for u in done.unknowns] == ["rc[0]"]


def test_a_chain_is_flat_and_prints_back():
    e = parse_as(".PROGRAM t()\n  x = a - b + c * d * e - f\n.END\n", "f.as").programs[0].body[0].value
    assert isinstance(e, ast.Chain) and [op for op, _ in e.rest] == ["-", "+", "-"]
    assert isinstance(e.rest[1][1], ast.Chain) and expr_text(e) == "a - b + c * d * e - f"
    two = parse_as(".PROGRAM t()\n  x = a + b\n.END\n", "f.as").programs[0].body[0].value
    assert two == ast.Binary("+", ast.Name("a"), ast.Name("b"))


@pytest.mark.parametrize("text,value", [
    ("10 - 4 - 3", 3.0), ("2 ^ 3 ^ 2", 512.0), ("64 / 4 / 2 * 3", 24.0), ("1 < 2 == -1", -1.0), ("3 > 2 > 1", 0.0),
    ("1 OR 0 XOR 1", 0.0), ("0 AND 1 AND 1", 0.0), ("5 BOR 2 BXOR 1", 6.0), ("7 MOD 4 MOD 2", 1.0),
    ('"a" == "a" == -1', -1.0), ("DX(p + q + p)", 12.0),
])
def test_chains_fold_left_to_right(text, value):
    assert value_of(text) == value


OPS = {"+": operator.add, "-": operator.sub, "*": operator.mul}


@settings(max_examples=100, deadline=None)
@given(st.lists(st.integers(-9, 9), min_size=2, max_size=40), st.data())
def test_a_flat_chain_agrees_with_pythons_left_fold(numbers, data):
    ops = data.draw(st.lists(st.sampled_from(["+", "-"]), min_size=len(numbers) - 1, max_size=len(numbers) - 1))
    text = str(numbers[0]) + "".join(f" {op} ({n})" for op, n in zip(ops, numbers[1:]))
    expected = reduce(lambda acc, pair: OPS[pair[0]](acc, pair[1]), zip(ops, numbers[1:]), numbers[0])
    assert value_of(text) == expected


@pytest.mark.parametrize("text", [
    "(" * 70 + "1" + ")" * 70, "-" * 600 + "1", "NOT " * 600 + "1", "2" + "^2" * 600, "SIN(" * 70 + "1" + ")" * 70,
    "a[" * 70 + "1" + "]" * 70,
])
def test_deep_nesting_is_one_line_naming_the_budget(text):
    with pytest.raises(AsSyntaxError) as info:
        parse_as(f".PROGRAM t()\n  x = {text}\n.END\n", "f.as")
    assert re.fullmatch(rf"f\.as:2:\d+: expression nested more than {MAX_DEPTH} deep", str(info.value))


@pytest.mark.parametrize("programs,cycle", [
    (".PROGRAM a()\n  CALL b\n.END\n.PROGRAM b()\n  CALL a\n.END\n", "a -> b -> a"),
    (".PROGRAM a()\n  CALL b\n.END\n.PROGRAM b()\n  CALL c\n.END\n.PROGRAM c()\n  x = x + 1\n  CALL b\n.END\n",
     "b -> c -> b"),
])
def test_a_call_cycle_is_named(programs, cycle):
    with pytest.raises(ExecutionError) as info:
        run_text(programs)
    assert f"CALLs nested more than 50 deep: the CALL cycle {cycle} never ends" in str(info.value)
    assert "\n" not in str(info.value)
