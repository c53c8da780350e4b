"""RAPID text -> modules: data declarations, PROC/FUNC/TRAP routines and their statements.

Accepted as real controllers save and people write them: any case, the ``%%% VERSION ...
%%%`` header of old ``.prg`` files, module attributes, ``LOCAL``/``TASK`` declarations,
compact ``IF``, ``ELSEIF``, ``TEST ... CASE ... DEFAULT``, labels and ``GOTO``, error and undo
handlers (kept apart), ``RECORD`` and ``ALIAS`` declarations (skipped), late binding ``%name%``.
Every error is an InputError naming file:line.
"""

from __future__ import annotations

from typing import Optional

from coatsim.core.errors import InputError
from coatsim.languages.abb_rapid import syntax as s
from coatsim.languages.script import nodes as n
from coatsim.languages.script.parse import Stream
from coatsim.languages.script.tokens import END, NAME, NEWLINE, OP, tokenize

_STORAGE = ("VAR", "PERS", "CONST")
_BLOCK_END = {"ENDIF", "ELSE", "ELSEIF", "ENDFOR", "ENDWHILE", "ENDTEST", "CASE", "DEFAULT", "ENDPROC", "ENDFUNC",
              "ENDTRAP", "ERROR", "UNDO", "BACKWARD"}


def _aggregate(st: Stream) -> n.Expr:
    line = st.expect_op("[").line
    items: list[n.Expr] = []
    st.skip_newlines()
    while not st.is_op("]"):
        items.append(st.expression())
        st.skip_newlines()
        if not st.accept_op(","):
            break
        st.skip_newlines()
    st.skip_newlines()
    st.expect_op("]", " to close the aggregate")
    return n.Aggregate(tuple(items), line)


def _argument(st: Stream) -> n.Arg:
    """A positional argument, ``\\Name:=value`` or the switch ``\\Name``."""
    if st.accept_op("\\"):
        name = st.expect_name("an optional argument's name").text
        if st.accept_op(":="):
            return n.Arg(st.expression(), name)
        return n.Arg(None, name)
    if st.is_op("*"):  # an unnamed (stored) position
        line = st.next().line
        return n.Arg(n.Name("*", line))
    return n.Arg(st.expression())


class _Parser:
    def __init__(self, text: str, source: str) -> None:
        tokens = [t for t in tokenize(text, s.SYNTAX, source) if t.kind != NEWLINE]
        self.st = Stream(tokens, source, s.GRAMMAR, aggregate=_aggregate, argument=_argument)
        self.source = source

    def error(self, message: str, line: Optional[int] = None) -> InputError:
        return self.st.error(message, line)

    # --- modules --------------------------------------------------------------------------
    def modules(self) -> tuple[s.Module, ...]:
        st = self.st
        self._skip_header()
        out = []
        while st.tok.kind != END:
            if not st.is_word("MODULE"):
                raise self.error(f"expected MODULE, found {st.shown()}")
            out.append(self.module())
            self._skip_header()
        if not out:
            raise InputError(f"{self.source}:1: no MODULE in the file")
        return tuple(out)

    def _skip_header(self) -> None:
        """The ``%%%`` ... ``%%%`` header of a saved .prg/.mod file."""
        st = self.st
        while st.is_op("%") and st.peek().text == "%" and st.peek(2).text == "%":
            st.next(), st.next(), st.next()
            while st.tok.kind != END and not (st.is_op("%") and st.peek().text == "%" and st.peek(2).text == "%"):
                st.next()
            if st.tok.kind == END:
                raise self.error("the %%% header is not closed by %%%")
            st.next(), st.next(), st.next()

    def module(self) -> s.Module:
        st = self.st
        line = st.expect_word("MODULE").line
        name = st.expect_name("the module's name").text
        attrs: list[str] = []
        if st.accept_op("("):
            while not st.accept_op(")"):
                attrs.append(st.expect_name("a module attribute").text.upper())
                st.accept_op(",")
        data, routines, records = [], [], []
        while not st.is_word("ENDMODULE"):
            if st.tok.kind == END:
                raise self.error(f"MODULE {name} (line {line}) has no ENDMODULE")
            storage_kw = None
            if st.is_word("LOCAL", "TASK", "SYSMODULE"):
                storage_kw = st.next()
            if st.is_word(*_STORAGE):
                data.append(self.declaration())
            elif st.is_word("PROC", "FUNC", "TRAP"):
                routines.append(self.routine())
            elif st.is_word("RECORD"):
                records.append(self._skip_to("ENDRECORD"))
            elif st.is_word("ALIAS"):
                while not st.accept_op(";"):
                    st.next()
            else:
                where = f" after {storage_kw.text}" if storage_kw else ""
                raise self.error(f"expected data (VAR, PERS, CONST) or a routine (PROC, FUNC, TRAP){where} in MODULE "
                                 f"{name}, found {st.shown()}")
        st.next()
        return s.Module(name, tuple(attrs), tuple(data), tuple(routines), line, self.source, tuple(records))

    def _skip_to(self, word: str) -> str:
        st = self.st
        st.next()
        name = st.expect_name().text
        while not st.accept_word(word):
            if st.tok.kind == END:
                raise self.error(f"RECORD {name} has no {word}")
            st.next()
        return name

    def declaration(self) -> s.DataDecl:
        st = self.st
        storage = st.next()
        type_ = st.expect_name("a data type").text
        name = st.expect_name("the data's name").text
        dims: tuple = ()
        if st.accept_op("{"):
            items = [st.expression()]
            while st.accept_op(","):
                items.append(st.expression())
            st.expect_op("}")
            dims = tuple(items)
        value = None
        if st.accept_op(":="):
            value = st.expression()
        st.expect_op(";", f" after the declaration of {name}")
        return s.DataDecl(storage.text.upper(), type_.lower(), name, dims, value, storage.line, self.source)

    # --- routines -------------------------------------------------------------------------
    def routine(self) -> s.Routine:
        st = self.st
        head = st.next()
        kind = head.text.upper()
        type_ = st.expect_name("the function's type").text.lower() if kind == "FUNC" else ""
        name = st.expect_name("the routine's name").text
        params: list[s.Param] = []
        if st.accept_op("("):
            while not st.accept_op(")"):
                params += self.parameters()
                st.accept_op(",")
        data, body, handlers = [], [], []
        end = "END" + kind
        while True:
            st_tok = st.tok
            if st_tok.kind == END:
                raise self.error(f"{kind} {name} (line {head.line}) has no {end}")
            if st.is_word(end):
                end_line = st.next().line
                break
            if st.is_word("ERROR", "UNDO", "BACKWARD") and not st.peek().text == ":=":
                handlers.append(st.next().text.upper())
                if st.is_op("("):
                    st.arguments()
                while not st.is_word(end) and st.tok.kind != END:
                    self.statement()  # parsed (errors found), not run
                continue
            if st.is_word("LOCAL"):
                st.next()
            if st.is_word(*_STORAGE):
                data.append(self.declaration())
                continue
            body.append(self.statement())
        return s.Routine(kind, name, type_, tuple(params), tuple(data), tuple(body), head.line, end_line, self.source,
                         tuple(handlers))

    def parameters(self) -> list[s.Param]:
        """One parameter, or a group of alternatives ``\\switch a | switch b``."""
        st = self.st
        optional = st.accept_op("\\")
        out = [self._parameter(optional)]
        while st.accept_op("|"):
            out.append(self._parameter(True))
        return out

    def _parameter(self, optional: bool) -> s.Param:
        st = self.st
        mode = "IN"
        if st.is_word("VAR", "PERS", "INOUT"):
            mode = st.next().text.upper()
        type_ = st.expect_name("a parameter's type").text.lower()
        name = st.expect_name("a parameter's name").text
        if st.accept_op("{"):
            while not st.accept_op("}"):
                st.next()
        return s.Param(name, type_, mode, optional)

    # --- statements -----------------------------------------------------------------------
    def block(self, *ends: str) -> tuple:
        st = self.st
        body = []
        while not st.is_word(*ends):
            if st.tok.kind == END:
                raise self.error(f"expected {' or '.join(ends)}, found the end of the file")
            body.append(self.statement())
        return tuple(body)

    def statement(self):
        st = self.st
        t = st.tok
        if t.kind == OP and t.text == "%":
            st.next()
            target = st.expression()
            st.expect_op("%")
            args = self._call_args()
            end_line = st.expect_op(";").line
            return s.ProcCall("%", args, t.line, end_line, late=target)
        if t.kind != NAME:
            raise self.error(f"expected a statement, found {st.shown()}")
        word = t.text.upper()
        if st.peek().kind == OP and st.peek().text == ":" and word not in _BLOCK_END:
            st.next(), st.next()
            return s.Label(t.text, t.line)
        handler = {"IF": self._if, "FOR": self._for, "WHILE": self._while, "TEST": self._test}.get(word)
        if handler is not None:
            return handler()
        if word == "GOTO":
            st.next()
            label = st.expect_name("a label").text
            st.expect_op(";")
            return s.Goto(label, t.line)
        if word == "RETURN":
            st.next()
            value = None if st.is_op(";") else st.expression()
            st.expect_op(";")
            return s.Return(value, t.line)
        if word == "CONNECT":
            st.next()
            target = st.expression()
            st.expect_word("WITH")
            trap = st.expect_name("a trap routine").text
            st.expect_op(";")
            return s.Connect(target, trap, t.line)
        if word in _BLOCK_END or word in ("ENDMODULE", "MODULE", "PROC", "FUNC", "TRAP"):
            raise self.error(f"{t.text} without the statement that opens it")
        # an assignment or a procedure call
        if st.peek().kind == OP and st.peek().text in (":=", ".", "{"):
            target = st.expression(s.GRAMMAR.binary["+"] + 10)  # a name with fields and indexes
            if st.accept_op(":="):
                value = st.expression()
                st.expect_op(";", " after the assignment")
                return s.Assign(target, value, t.line)
            raise self.error(f"expected ':=' after {t.text}, found {st.shown()}")
        st.next()
        args = self._call_args()
        end_line = st.expect_op(";", f" after {t.text}").line
        return s.ProcCall(t.text, args, t.line, end_line)

    def _call_args(self) -> tuple[n.Arg, ...]:
        st = self.st
        args: list[n.Arg] = []
        while not st.is_op(";"):
            if st.tok.kind == END:
                raise self.error("expected ';' at the end of the statement")
            args.append(_argument(st))
            if not st.accept_op(",") and not st.is_op("\\") and not st.is_op(";"):
                raise self.error(f"expected ',' or ';' between arguments, found {st.shown()}")
        return tuple(args)

    def _if(self):
        st = self.st
        line = st.next().line
        cond = st.expression()
        if not st.accept_word("THEN"):  # compact IF: one statement
            inner = self.statement()
            return s.If(((cond, (inner,)),), (), line, getattr(inner, "end_line", inner.line))
        branches = [(cond, self.block("ELSEIF", "ELSE", "ENDIF"))]
        orelse: tuple = ()
        while True:
            if st.accept_word("ELSEIF"):
                c = st.expression()
                st.expect_word("THEN")
                branches.append((c, self.block("ELSEIF", "ELSE", "ENDIF")))
            elif st.accept_word("ELSE"):
                orelse = self.block("ENDIF")
            else:
                end = st.expect_word("ENDIF").line
                return s.If(tuple(branches), orelse, line, end)

    def _for(self):
        st = self.st
        line = st.next().line
        var = st.expect_name("the loop variable").text
        st.expect_word("FROM")
        start = st.expression()
        st.expect_word("TO")
        stop = st.expression()
        step = st.expression() if st.accept_word("STEP") else None
        st.expect_word("DO")
        body = self.block("ENDFOR")
        end = st.next().line
        return s.For(var, start, stop, step, body, line, end)

    def _while(self):
        st = self.st
        line = st.next().line
        cond = st.expression()
        st.expect_word("DO")
        body = self.block("ENDWHILE")
        end = st.next().line
        return s.While(cond, body, line, end)

    def _test(self):
        st = self.st
        line = st.next().line
        value = st.expression()
        cases, default = [], None
        while True:
            if st.accept_word("CASE"):
                values = [st.expression()]
                while st.accept_op(","):
                    values.append(st.expression())
                st.expect_op(":")
                cases.append((tuple(values), self.block("CASE", "DEFAULT", "ENDTEST")))
            elif st.accept_word("DEFAULT"):
                st.expect_op(":")
                default = self.block("CASE", "DEFAULT", "ENDTEST")
            else:
                end = st.expect_word("ENDTEST").line
                return s.Test(value, tuple(cases), default, line, end)


def parse_rapid(text: str, source: str) -> tuple[s.Module, ...]:
    """The modules of one RAPID file; InputError naming ``source``:line on any defect."""
    return _Parser(text, source).modules()
