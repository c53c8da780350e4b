"""KRL text -> routines (``DEF``/``DEFFCT`` ... ``END``/``ENDFCT``) and data lists (``DEFDAT`` ...
``ENDDAT``): one statement per line, ``;`` comments (``;FOLD``/``;ENDFOLD`` are comments around
code that runs), ``&ACCESS``/``&REL`` header lines skipped, any case (KUKA System Software 8,
"Programming for system integrators": KRL syntax). Statements are kept as their tokens with
their line; the interpreter reads them (:mod:`.interpreter`)."""

from __future__ import annotations

from dataclasses import dataclass

from coatsim.core.errors import InputError
from coatsim.languages.script import nodes as n
from coatsim.languages.script.parse import Grammar, Stream
from coatsim.languages.script.tokens import END, NAME, NEWLINE, OP, Syntax, Token, tokenize

SYNTAX = Syntax(comment=";", name_start="$#", operators=("==", "<>", "<=", ">=", "=", "<", ">", "+", "-", "*", "/",
                                                         ":", "(", ")", "[", "]", "{", "}", ",", ".", "'"))
GRAMMAR = Grammar(binary={"OR": 1, "EXOR": 1, "B_OR": 1, "B_EXOR": 1, "AND": 2, "B_AND": 2, "==": 4, "<>": 4,
                          "<": 4, ">": 4, "<=": 4, ">=": 4, "+": 5, "-": 5, "*": 6, "/": 6, ":": 7},
                  unary={"NOT": 3, "B_NOT": 3, "-": 8, "+": 8}, index_open="[", index_close="]", aggregate_open="{")


@dataclass(frozen=True)
class Line:
    """One statement: its tokens (no newline) and line number."""

    tokens: tuple[Token, ...]
    line: int

    @property
    def word(self) -> str:
        return self.tokens[0].text.upper() if self.tokens and self.tokens[0].kind == NAME else ""


@dataclass(frozen=True)
class Routine:
    kind: str  # DEF or DEFFCT
    name: str
    params: tuple[str, ...]
    body: tuple[Line, ...]
    line: int
    end_line: int
    source: str
    is_global: bool


@dataclass(frozen=True)
class DataList:
    name: str
    body: tuple[Line, ...]
    line: int
    source: str


def aggregate(st: Stream) -> n.Expr:
    """``{X 1, Y 2}`` or ``{E6POS: X 1, ...}``: named components, nested aggregates."""
    line = st.expect_op("{").line
    type_ = ""
    if st.tok.kind == NAME and st.peek().text == ":":
        type_ = st.next().text.upper()
        st.next()
    fields, items = [], []
    while not st.is_op("}"):
        name = st.expect_name("a component name").text.upper()
        if st.accept_op("["):  # a CHAR array component: POINT2[] "P1"
            st.expect_op("]", " after '[' of a text component")
        fields.append(name)
        items.append(st.expression(GRAMMAR.binary[":"] + 1))
        if not st.accept_op(","):
            break
    if not st.is_op("}") and st.tok.kind == OP and st.tok.text in "+-*/":
        raise st.error(f"an aggregate holds values, not expressions (KRL): set the component after, "
                       f"e.g. p.{fields[-1] if fields else 'X'} = ...")
    st.expect_op("}", " to close the aggregate")
    return n.Aggregate(tuple(items), line, tuple(fields), type_)


def stream(tokens, source: str) -> Stream:
    return Stream(list(tokens) + [Token(END, "", tokens[-1].line if tokens else 0)], source, GRAMMAR, aggregate)


def _lines(text: str, source: str) -> list[Line]:
    text = "\n".join("" if raw.lstrip().startswith("&") else raw for raw in text.splitlines())
    out, current = [], []
    for t in tokenize(text, SYNTAX, source):
        if t.kind in (NEWLINE, END):
            if current:
                out.append(Line(tuple(current), current[0].line))
            current = []
        else:
            current.append(t)
    return out


def parse_krl(text: str, source: str) -> tuple[tuple[Routine, ...], tuple[DataList, ...]]:
    """The routines and data lists of one KRL file; InputError naming ``source``:line."""
    lines = _lines(text, source)
    routines, datas = [], []
    k = 0
    while k < len(lines):
        ln = lines[k]
        words = [t.text.upper() for t in ln.tokens if t.kind == NAME]
        is_global = bool(words) and words[0] == "GLOBAL"
        head = words[1] if is_global and len(words) > 1 else (words[0] if words else "")
        if head in ("DEF", "DEFFCT"):
            end = "END" if head == "DEF" else "ENDFCT"
            j = k + 1
            while j < len(lines) and lines[j].word != end:
                j += 1
            if j == len(lines):
                raise InputError(f"{source}:{ln.line}: {head} without {end}")
            names = [t for t in ln.tokens if t.kind == NAME]
            skip = 1 + is_global + (head == "DEFFCT")  # DEFFCT has a return type before the name
            if len(names) < skip + 1:
                raise InputError(f"{source}:{ln.line}: {head} needs a name")
            name = names[skip].text
            params = tuple(t.text for t in names[skip + 1:] if t.text.upper() not in ("IN", "OUT"))
            routines.append(Routine(head, name, params, tuple(lines[k + 1:j]), ln.line, lines[j].line, source,
                                    is_global or not routines))
            k = j + 1
        elif head == "DEFDAT":
            j = k + 1
            while j < len(lines) and lines[j].word != "ENDDAT":
                j += 1
            if j == len(lines):
                raise InputError(f"{source}:{ln.line}: DEFDAT without ENDDAT")
            names = [t for t in ln.tokens if t.kind == NAME]
            datas.append(DataList(names[1].text if len(names) > 1 else "", tuple(lines[k + 1:j]), ln.line, source))
            k = j + 1
        else:
            raise InputError(f"{source}:{ln.line}: expected DEF, DEFFCT or DEFDAT, found {ln.tokens[0].text!r}")
    if not routines and not datas:
        raise InputError(f"{source}:1: no DEF or DEFDAT in the file")
    return tuple(routines), tuple(datas)


def split_commas(tokens) -> list[list]:
    """Tokens split at the commas outside brackets."""
    out, current, depth = [], [], 0
    for t in tokens:
        if t.kind == OP and t.text in "([{":
            depth += 1
        elif t.kind == OP and t.text in ")]}":
            depth -= 1
        if t.kind == OP and t.text == "," and depth == 0:
            out.append(current)
            current = []
        else:
            current.append(t)
    if current:
        out.append(current)
    return out


def statement_text(tokens) -> str:
    """A statement's tokens as written (a space only between two words or numbers)."""
    out, prev = "", None
    for t in tokens:
        if prev is not None and prev.kind in (NAME, "num") and t.kind in (NAME, "num"):
            out += " "
        out += t.text
        prev = t
    return out
