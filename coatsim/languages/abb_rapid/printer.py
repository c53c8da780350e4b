"""RAPID syntax back to text (for check-program's list of output switches)."""

from __future__ import annotations

from coatsim.languages.abb_rapid import syntax as s
from coatsim.languages.script import nodes as n


def expr_text(e: n.Expr) -> str:
    if isinstance(e, n.Num):
        return f"{e.value:g}"
    if isinstance(e, n.Str):
        return f'"{e.value}"'
    if isinstance(e, n.Name):
        return e.name
    if isinstance(e, n.Field):
        return f"{expr_text(e.base)}.{e.field}"
    if isinstance(e, n.Index):
        return f"{expr_text(e.base)}{{{', '.join(expr_text(i) for i in e.index)}}}"
    if isinstance(e, n.Call):
        return f"{e.name}({', '.join(arg_text(a) for a in e.args)})"
    if isinstance(e, n.Unary):
        return f"{e.op}{' ' if e.op.isalpha() else ''}{expr_text(e.operand)}"
    if isinstance(e, n.Binary):
        return f"{expr_text(e.left)} {e.op} {expr_text(e.right)}"
    if isinstance(e, n.Aggregate):
        return f"[{', '.join(expr_text(i) for i in e.items)}]"
    return "?"


def arg_text(a: n.Arg) -> str:
    if a.name is None:
        return expr_text(a.value)
    return f"\\{a.name}" + ("" if a.value is None else f":={expr_text(a.value)}")


def call_text(st: s.ProcCall) -> str:
    return f"{st.name} {', '.join(arg_text(a) for a in st.args)}".rstrip()
