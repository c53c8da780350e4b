"""Expressions: precedence, AS truth values, every built-in function, and a property test:
for random expressions the interpreter agrees with Python's evaluation of the same tree."""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.kawasaki_as import ast, parse_as
from coatsim.languages.kawasaki_as.interpreter import Interpreter
from coatsim.languages.kawasaki_as.printer import expr_text

PROGRAM = ".PROGRAM t()\n{body}\n.END\n.TRANS\np 10 20 30 0 90 0\nq 13 24 30 0 90 0\n.END\n.REALS\nr = 2\n.END\n"


def evaluate(expression: str, kind: str = "real"):
    """The value of an expression as the interpreter computes it (assigned to a global)."""
    target = "x" if kind == "real" else "$x"
    f = parse_as(PROGRAM.format(body=f"  {target} = {expression}"), "e.as")
    run = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    run.run(f.programs[0])
    return run.globals.get(kind, target)


PRECEDENCE = [
    ("1 + 2 * 3", 7.0), ("(1 + 2) * 3", 9.0), ("2 ^ 3 ^ 2", 512.0), ("-2 ^ 2", -4.0), ("7 MOD 4 * 2", 6.0),
    ("1 + 2 == 3", -1.0), ("NOT 1 == 2", -1.0), ("1 == 1 AND 2 > 3", 0.0), ("1 == 1 OR 2 > 3", -1.0),
    ("TRUE XOR ON", 0.0), ("6 BAND 3", 2.0), ("6 BOR 3", 7.0), ("6 BXOR 3", 5.0), ("12 BAND 4 == 4", -1.0),
    ("-7 MOD 3", -1.0), ("10 / 4", 2.5), ("r * 3", 6.0), (".5 + 125.", 125.5), ("^HFF BAND ^B1010", 10.0),
]


@pytest.mark.parametrize("text,value", PRECEDENCE)
def test_precedence_and_operators(text, value):
    assert evaluate(text) == value


FUNCTIONS = [
    ("SIN(30)", 0.5), ("COS(60)", 0.5), ("TAN(45)", 1.0), ("ATAN2(1, 1)", 45.0), ("ASIN(1)", 90.0),
    ("SQRT(16)", 4.0), ("ABS(-3)", 3.0), ("INT(-2.7)", -2.0), ("INT(2.7)", 2.0), ("MAXVAL(1, 5, 3)", 5.0),
    ("MINVAL(4, -1)", -1.0), ("LEN(\"abc\")", 3.0), ("ASC(\"A\")", 65.0), ("ASC(\"AB\", 2)", 66.0),
    ("VAL(\"12.5mm\")", 12.5), ("INSTR(\"a,b,c\", \",\")", 2.0), ("INSTR(3, \"a,b,c\", \",\")", 4.0),
    ("DISTANCE(p, q)", 5.0), ("DX(p)", 10.0), ("DY(q)", 24.0), ("DZ(SHIFT(p BY 0, 0, 5))", 35.0),
    ("DEXT(p, 5)", 90.0), ("DX(p + TRANS(0, 0, 10))", 20.0), ("DX(-p + p)", 0.0), ("SIG(1)", 0.0),
    ("SIG(-1)", -1.0), ("MSPEED", 100.0), ("PI", math.pi), ("DX(NULL)", 0.0), ("DZ(RX(90) + TRANS(0, 1, 0))", 1.0),
    ("EXISTREAL(\"r\")", -1.0), ("EXISTTRANS(\"nothere\")", 0.0), ("EXISTPGM(\"t\")", -1.0),
    ("BITS(1, 4)", 0.0), ("DX(FRAME(p, q, TRANS(0, 99, 30), p))", 10.0),
    ("BCD(1234)", 0x1234), ("DCB(^H1234)", 1234.0), ("DCB(BCD(907))", 907.0), ("BCD(0)", 0.0),
]


@pytest.mark.parametrize("text,value", FUNCTIONS)
def test_functions(text, value):
    assert evaluate(text) == pytest.approx(value, abs=1e-9)


STRINGS = [
    ('$MID("abcdef", 2, 3)', "bcd"), ('$LEFT("abc", 2)', "ab"), ('$RIGHT("abc", 2)', "bc"), ("$CHR(65)", "A"),
    ("$SPACE(3)", "   "), ('"a" + "b"', "ab"), ("$ENCODE(/D, 3.7, \" \", /F6.2, r)", "4   2.00"),
    ('$ENCODE("x=", /F5.1, 2.25)', "x=  2.2"),
]


@pytest.mark.parametrize("text,value", STRINGS)
def test_string_functions(text, value):
    assert evaluate(text, "string") == value


def test_decode_takes_its_string_by_reference():
    f = parse_as(PROGRAM.format(body='  $s = "12,34"\n  $a = $DECODE(&$s, ",", 0)\n  $b = $DECODE(&$s, ",", 1)\n'
                                     '  x = VAL($a) + VAL($s)'), "e.as")
    run = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    run.run(f.programs[0])
    assert run.globals.get("real", "x") == 46.0 and run.globals.get("string", "$b") == ","


ERRORS = [
    ("1 / 0", ExecutionError, "division by zero"), ("SQRT(-1)", ExecutionError, "no real value"),
    ("5 MOD 0", ExecutionError, "MOD by zero"), ("(-8) ^ 0.5", ExecutionError, "no real value"),
    ("p + 1", InputError, "is a pose variable"),
    ('"a" + 1', InputError, "expected a number, found a string"), ("SIN(1, 2)", InputError, "takes 1 argument"),
    ("LEN(1)", InputError, "expected a string, found a number"), ("10 ^ 400", ExecutionError, "no real value"),
    ("$MID(\"a\") + \"b\"", InputError, "needs argument 2"), ("p", InputError, "is a pose variable"),
    ("BCD(-1)", ExecutionError, "from 0 to 99999999"), ("DCB(^H1A)", ExecutionError, "not a binary-coded decimal"),
]


@pytest.mark.parametrize("text,kind,words", ERRORS)
def test_errors(text, kind, words):
    with pytest.raises(kind) as info:
        evaluate(text, "string" if text.startswith("$") else "real")
    assert words in str(info.value) and str(info.value).startswith("e.as:2: ")


# --- property: random expressions ---------------------------------------------------------
LEAVES = st.one_of(st.integers(-20, 20).map(float), st.sampled_from([0.5, 2.25, -1.5, 0.125, 10.0]))


def trees(depth: int = 4):
    leaf = LEAVES.map(ast.Num)
    ops = ["+", "-", "*", "/", "MOD", "==", "<>", "<", ">", "<=", ">=", "AND", "OR", "XOR", "BAND", "BOR", "BXOR", "^"]

    def extend(children):
        return st.one_of(
            st.tuples(st.sampled_from(ops), children, children).map(lambda t: ast.Binary(*t)),
            st.tuples(st.sampled_from(["-", "NOT"]), children).map(lambda t: ast.Unary(*t)),
            st.tuples(st.sampled_from(["ABS", "INT", "SIN", "COS"]), children).map(lambda t: ast.Call(t[0], (t[1],))),
            st.tuples(children, children).map(lambda t: ast.Call("MAXVAL", t)),
        )
    return st.recursive(leaf, extend, max_leaves=12)


class _Undefined(Exception):
    pass


def python_value(e) -> float:
    """Python's evaluation of the tree, with AS truth values (-1, 0)."""
    t = lambda b: -1.0 if b else 0.0  # noqa: E731
    if isinstance(e, ast.Num):
        return e.value
    if isinstance(e, ast.Unary):
        v = python_value(e.operand)
        return -v if e.op == "-" else t(v == 0)
    if isinstance(e, ast.Call):
        vals = [python_value(a) for a in e.args]
        f = {"ABS": abs, "INT": lambda x: float(math.trunc(x)), "SIN": lambda x: math.sin(math.radians(x)),
             "COS": lambda x: math.cos(math.radians(x)), "MAXVAL": lambda *x: max(x)}[e.name]
        return f(*vals)
    a, b = python_value(e.left), python_value(e.right)
    op = e.op
    if op in ("/", "MOD") and b == 0:
        raise _Undefined
    if op == "^":
        try:
            out = math.pow(a, b)
        except (ValueError, OverflowError):
            raise _Undefined from None
        if not math.isfinite(out):
            raise _Undefined
        return out
    table = {
        "+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b, "/": lambda: a / b, "MOD": lambda: math.fmod(a, b),
        "==": lambda: t(a == b), "<>": lambda: t(a != b), "<": lambda: t(a < b), ">": lambda: t(a > b),
        "<=": lambda: t(a <= b), ">=": lambda: t(a >= b), "AND": lambda: t(a != 0 and b != 0),
        "OR": lambda: t(a != 0 or b != 0), "XOR": lambda: t((a != 0) != (b != 0)),
        "BAND": lambda: float(math.trunc(a) & math.trunc(b)), "BOR": lambda: float(math.trunc(a) | math.trunc(b)),
        "BXOR": lambda: float(math.trunc(a) ^ math.trunc(b)),
    }
    out = table[op]()
    if not math.isfinite(out):
        raise _Undefined
    return out


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(trees())
def test_interpreter_agrees_with_python(tree):
    try:
        expected = python_value(tree)
    except _Undefined:
        with pytest.raises(ExecutionError):
            evaluate(expr_text(tree))
        return
    got = evaluate(expr_text(tree))
    assert got == pytest.approx(expected, rel=1e-12, abs=1e-12), expr_text(tree)
