"""Instruction words as programs hold them: in any case, and abbreviated.

The controller takes an instruction word shortened to a leading part of it (``TY`` for TYPE,
``SPE`` for SPEED, ``LDEP`` for LDEPART) and files hand-written in an editor keep that form. The
rule applied: a word that is an instruction is that instruction; otherwise it stands for the one
instruction it starts, or, when it starts several that all extend one of them (``RET``: RETURN,
RETURNE), for that shortest one; a start shared by unrelated instructions (``ACC``: ACCEL,
ACCURACY) is ambiguous and names them.
"""

from __future__ import annotations

from bisect import bisect_left
from typing import Iterable, Optional


class Keywords:
    """The instruction words of the language, with their abbreviations."""

    def __init__(self, words: Iterable[str]) -> None:
        self.words = sorted(set(words))
        self.known = frozenset(self.words)
        self.cache: dict[str, tuple[str, ...]] = {}

    def starting(self, prefix: str) -> tuple[str, ...]:
        """The instruction words that start with ``prefix`` (upper case)."""
        found = self.cache.get(prefix)
        if found is None:
            i = bisect_left(self.words, prefix)
            out = []
            while i < len(self.words) and self.words[i].startswith(prefix):
                out.append(self.words[i])
                i += 1
            found = self.cache[prefix] = tuple(out)
        return found

    def expand(self, word: str) -> tuple[Optional[str], tuple[str, ...]]:
        """(the instruction ``word`` stands for or None, the instructions it starts)."""
        if word in self.known:
            return word, (word,)
        matches = self.starting(word)
        if matches and all(m.startswith(matches[0]) for m in matches):
            return matches[0], matches  # sorted: the shortest comes first
        return None, matches
