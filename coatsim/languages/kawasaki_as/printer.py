"""AS text of expressions, with the fewest parentheses the grammar needs (messages, listings)."""

from __future__ import annotations

from coatsim.languages.kawasaki_as import ast

_POWER = {"OR": 1, "XOR": 1, "AND": 2, "==": 4, "<>": 4, "<": 4, ">": 4, "<=": 4, ">=": 4, "BOR": 5, "BXOR": 5,
          "BAND": 6, "+": 7, "-": 7, "*": 8, "/": 8, "MOD": 8, "^": 10}
_PRIMARY = 11


def _number(x: float) -> str:
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


def _power(e: ast.Expr) -> int:
    if isinstance(e, ast.Binary):
        return _POWER[e.op]
    if isinstance(e, ast.Chain):
        return _POWER[e.rest[0][0]]
    if isinstance(e, ast.Unary):
        return 3 if e.op == "NOT" else 9
    if isinstance(e, ast.Num) and e.value < 0:
        return 9
    return _PRIMARY


def _wrap(e: ast.Expr, need: int) -> str:
    text = expr_text(e)
    return f"({text})" if _power(e) < need else text


def _args(args) -> str:
    return ", ".join("" if a is None else expr_text(a) for a in args)


def _brackets(name: ast.Name) -> str:
    return "[]" if name.whole else f"[{_args(name.index)}]" if name.index else ""


def expr_text(e: ast.Expr) -> str:
    """AS source text of ``e``; parsing it gives back ``e``."""
    if isinstance(e, ast.Num):
        return _number(e.value)
    if isinstance(e, ast.Str):
        return f'"{e.value}"'
    if isinstance(e, ast.Name):
        return e.name + _brackets(e)
    if isinstance(e, ast.Ref):
        name = e.target.name
        return ("." + "&" + name[1:] if name.startswith(".") else "&" + name) + _brackets(e.target)
    if isinstance(e, ast.Format):
        return f"/{e.spec}"
    if isinstance(e, ast.Unary):
        if e.op == "NOT":
            return f"NOT {_wrap(e.operand, 3)}"
        return f"{e.op}{_wrap(e.operand, 9)}"
    if isinstance(e, ast.Binary):
        p = _POWER[e.op]
        right_assoc = e.op == "^"
        left = _wrap(e.left, p + 1 if right_assoc else p)
        right = _wrap(e.right, p if right_assoc else p + 1)
        return f"{left} {e.op} {right}"
    if isinstance(e, ast.Chain):
        p = _POWER[e.rest[0][0]]
        return " ".join([_wrap(e.first, p), *(f"{op} {_wrap(x, p + 1)}" for op, x in e.rest)])
    if isinstance(e, ast.Call):
        return e.name if not e.args and e.name in ("NULL", "HERE", "#HERE", "DEST", "#DEST") else f"{e.name}({_args(e.args)})"
    if isinstance(e, ast.Shift):
        return f"SHIFT({expr_text(e.base)} BY {_args(e.delta)})"
    if isinstance(e, ast.JointLiteral):
        return f"#[{_args(e.values)}]"
    raise TypeError(f"not an expression: {e!r}")
