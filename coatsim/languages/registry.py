"""The robot languages coatsim writes and reads, by name and by file suffix.

Adding a language is one package under ``coatsim.languages`` implementing
:class:`coatsim.path.language.Language` and one entry in ``LANGUAGES`` below. A language is
named by its full name (``abb-rapid``) or by any part of it no other language's name has
(``rapid``, ``abb``). Files are read in the language their suffix names; where several
languages claim a suffix, or none does, the opening of the first file decides
(:meth:`~coatsim.path.language.Language.recognizes`).
"""

from __future__ import annotations

import os
from collections import Counter
from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.core.fileio import decode_text, open_input
from coatsim.languages.abb_rapid.language import ABB_RAPID
from coatsim.languages.fanuc_tp.language import FANUC_TP
from coatsim.languages.gcode.language import GCODE
from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.languages.kuka_krl.language import KUKA_KRL
from coatsim.languages.urscript.language import URSCRIPT
from coatsim.path.language import Language

LANGUAGES: dict[str, Language] = {language.name: language for language in (
    KAWASAKI_AS,
    ABB_RAPID,
    KUKA_KRL,
    FANUC_TP,
    URSCRIPT,
    GCODE,
)}
#: The language coatsim writes when none is asked for.
DEFAULT_LANGUAGE = KAWASAKI_AS.name
SNIFF_BYTES = 8192  # how much of a file's opening tells its language


def _aliases() -> dict[str, str]:
    """Each part of a language's name that no other name has (``rapid`` for ``abb-rapid``)."""
    parts = Counter(part for name in LANGUAGES for part in set(name.split("-")))
    return {part: name for name in LANGUAGES for part in name.split("-") if parts[part] == 1 and part not in LANGUAGES}


def language(name: str) -> Language:
    """The language called ``name`` (or a part of its name only it has); InputError listing the
    valid names otherwise."""
    key = name.strip().lower()
    found = LANGUAGES.get(key) or LANGUAGES.get(_aliases().get(key, ""))
    if found is None:
        raise InputError(f"language {name!r}: expected one of {', '.join(LANGUAGES)}", parameters=("language",))
    return found


def _opening(path: Path) -> str:
    try:
        with open_input(path, "program") as fd:  # never blocks on a FIFO, never reads a device
            return decode_text(os.read(fd, SNIFF_BYTES))
    except (InputError, OSError):
        return ""  # reading the file proper says what is wrong with it


def language_of(files: Sequence[str | Path], name: str | None = None) -> Language:
    """The language to read ``files`` with: ``name`` if given, else the one whose suffixes
    include the files' suffixes, else (a suffix several languages or none claim) the one that
    recognizes the opening of the first file, else the default language."""
    if name is not None:
        return language(name)
    suffixes = {Path(f).suffix.lower() for f in files}
    claimed = [lang for lang in LANGUAGES.values() if suffixes & set(lang.suffixes)]
    if len(claimed) == 1:
        return claimed[0]
    candidates = claimed or list(LANGUAGES.values())
    opening = _opening(Path(files[0])) if files else ""
    recognized = [lang for lang in candidates if lang.recognizes(opening)]
    if len(recognized) == 1:
        return recognized[0]
    if len(claimed) > 1:
        raise InputError(f"program files of several languages ({', '.join(l.name for l in claimed)}): "
                         "read one language at a time, or name it (language)", parameters=("language",))
    return LANGUAGES[DEFAULT_LANGUAGE]
