"""The opening comments of a written program in the languages that write them one a line (RAPID,
KRL): the plan's comments, then its process record as ``coatsim: key=value``, each after the
language's comment mark."""

from __future__ import annotations

from coatsim.languages.script.names import sanitize_comment
from coatsim.path.plan import ProgramPlan
from coatsim.path.process_record import encode


def header_comments(plan: ProgramPlan, mark: str) -> list[str]:
    """The comment lines, each starting with ``mark`` (``  ! `` in RAPID, ``;`` in KRL)."""
    return ([f"{mark}{sanitize_comment(c)}" for c in plan.comments]
            + [f"{mark}coatsim: {sanitize_comment(k)}={sanitize_comment(v, None)}" for k, v in encode(plan.process)])
