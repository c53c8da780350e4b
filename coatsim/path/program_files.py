"""Saving a written program: the file (or files, KRL's ``.src`` and ``.dat``) its text becomes."""

from __future__ import annotations

from pathlib import Path

from coatsim.core.fileio import write_text
from coatsim.path.language import Language


def program_suffixes(language: Language) -> tuple[str, ...]:
    """The suffixes of the files one written program of ``language`` is saved as, the main first."""
    return language.capabilities.program_files or (language.suffixes[0],)


def program_paths(language: Language, main: Path) -> tuple[Path, ...]:
    """The files a program saved as ``main`` occupies: ``main`` and its companions beside it
    (the same stem, the language's other suffixes)."""
    main = Path(main)
    return (main, *(main.with_suffix(suffix) for suffix in program_suffixes(language)[1:]))


def write_program(language: Language, text: str, main: Path) -> tuple[Path, ...]:
    """Save ``text`` (written by ``language``) as ``main`` and its companion files; the paths
    written, the main first. Each file is written atomically (coatsim.core.fileio)."""
    paths = program_paths(language, main)
    for path, (_, body) in zip(paths, language.files(text)):
        write_text(path, body)
    return paths
