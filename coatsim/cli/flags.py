"""Flag wording: library errors name parameters in the library's terms (``tolerance_mm``); a
command says them as its flags (``--tol``), here and nowhere else."""

from __future__ import annotations

from contextlib import contextmanager
from typing import Iterator, Mapping, NoReturn

from coatsim.core.errors import CoatsimError, InputError


def fail(message: str) -> NoReturn:
    """Stop the command with a one-line usage error (exit 2)."""
    raise InputError(message)


@contextmanager
def speaking_flags(flags: Mapping[str, str]) -> Iterator[None]:
    """Inside: a CoatsimError naming a parameter in ``flags`` is re-raised with the flag's name."""
    try:
        yield
    except CoatsimError as exc:
        if not any(name in flags for name in exc.parameters):
            raise
        raise exc.reworded(flags) from None



def budget_words(error: CoatsimError) -> dict[str, str]:
    """How the command line says the budgets an error names: ``coatsim --budget NAME=N``."""
    prefix = "the budget "
    return {p: f"the budget with coatsim --budget {p[len(prefix):]}=N" for p in error.parameters if p.startswith(prefix)}
