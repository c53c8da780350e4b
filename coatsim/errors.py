"""Errors a user can cause, each with the exit code the CLI returns for it.

Exit codes: 0 success; 1 a gate failed; 2 invalid input; 3 cannot execute.
"""

from __future__ import annotations


class CoatsimError(Exception):
    """Base of every error coatsim reports to a user; the message is one line."""

    exit_code: int = 2


class InputError(CoatsimError):
    """Invalid input: usage, file, schema or program syntax (exit 2)."""

    exit_code = 2


class ExecutionError(CoatsimError):
    """The program cannot execute: unreachable pose, joint limit, infeasible timing (exit 3)."""

    exit_code = 3


class GateFailure(CoatsimError):
    """An accuracy gate failed (exit 1)."""

    exit_code = 1
