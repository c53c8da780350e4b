"""Saving a written program: the file (or files, KRL's ``.src`` and ``.dat``) its text becomes."""

from __future__ import annotations

from pathlib import Path

from coatsim.core.errors import InputError
from coatsim.core.fileio import write_text
from coatsim.path.language import Language


def program_suffixes(language: Language) -> tuple[str, ...]:
    """The suffixes of the files one written program of ``language`` is saved as, the main first."""
    return language.capabilities.program_files or (language.suffixes[0],)


def program_paths(language: Language, main: Path) -> tuple[Path, ...]:
    """The files a program saved as ``main`` occupies: ``main`` and its companions beside it
    (the same stem, the language's other suffixes). A program of several files must be saved
    under its main suffix (InputError otherwise): the controller pairs them by name, and a KRL
    program saved as ``cap`` and ``cap.dat`` is neither loaded nor read back."""
    main = Path(main)
    suffixes = program_suffixes(language)
    if len(suffixes) > 1 and main.suffix.lower() != suffixes[0]:
        raise InputError(f"{main}: a {language.title} program is saved as {' and '.join('NAME' + s for s in suffixes)}; "
                         f"name the output {main.with_suffix(suffixes[0]).name}", parameters=("output",))
    return (main, *(main.with_suffix(suffix) for suffix in suffixes[1:]))


def write_program(language: Language, text: str, main: Path) -> tuple[Path, ...]:
    """Save ``text`` (written by ``language``) as ``main`` and its companion files; the paths
    written, the main first. Each file is written atomically (coatsim.core.fileio)."""
    paths = program_paths(language, main)
    for path, (_, body) in zip(paths, language.files(text)):
        write_text(path, body)
    return paths
