"""The robot languages coatsim writes and reads, by name and by file suffix.

Adding a language is one package under ``coatsim.languages`` implementing
:class:`coatsim.path.language.Language` and one entry in ``LANGUAGES`` below.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.path.language import Language

LANGUAGES: dict[str, Language] = {language.name: language for language in (KAWASAKI_AS,)}
#: The language coatsim writes when none is asked for.
DEFAULT_LANGUAGE = KAWASAKI_AS.name


def language(name: str) -> Language:
    """The language called ``name``; InputError listing the valid names otherwise."""
    try:
        return LANGUAGES[name]
    except KeyError:
        raise InputError(f"language {name!r}: expected one of {', '.join(LANGUAGES)}") from None


def language_of(files: Sequence[str | Path], name: str | None = None) -> Language:
    """The language to read ``files`` with: ``name`` if given, else the one whose suffixes
    include the files' suffix (the default language for a suffix no language claims)."""
    if name is not None:
        return language(name)
    suffixes = {Path(f).suffix.lower() for f in files}
    claimed = [lang for lang in LANGUAGES.values() if suffixes & set(lang.suffixes)]
    if len(claimed) > 1:
        raise InputError(f"program files of several languages ({', '.join(l.name for l in claimed)}): "
                         "read one language at a time")
    return claimed[0] if claimed else LANGUAGES[DEFAULT_LANGUAGE]
