"""What the fuzz tests of the readers share: a reader never fails with anything but a one-line
InputError (or an ExecutionError for what the twin cannot run) naming the file, whatever the
bytes. ``fuzz_tests`` makes the three tests every reader gets: random bytes, a soup of the
language's words inside a program, words spliced into a program coatsim wrote."""

from __future__ import annotations

from typing import Callable

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import ExecutionError, InputError
from coatsim.path.language import Language, ReadOptions

SETTINGS = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def read_fuzzed(language: Language, data: bytes, folder, suffix: str, options: ReadOptions = ReadOptions(),
                also_starts: tuple[str, ...] = ()) -> None:
    """Read ``data`` as a program file; only a one-line error naming the file (or starting with one
    of ``also_starts``) may come out."""
    path = folder / f"fuzz{suffix}"
    path.write_bytes(data)
    try:
        language.read([path], options)
    except (InputError, ExecutionError) as exc:
        text = str(exc)
        assert "\n" not in text, text
        assert text.startswith((str(path), *also_starts)), text


def fuzz_tests(read: Callable[[bytes, object], None], words: list[str], golden: bytes,
               program: Callable[[str], str], soup_size: int = 60):
    """The three tests: ``read(data, folder)`` reads bytes; ``program(body)`` puts a word soup in
    a program of the language."""

    @SETTINGS
    @given(data=st.binary(max_size=400))
    def test_random_bytes(data, tmp_path_factory):
        read(data, tmp_path_factory.mktemp("f"))

    @SETTINGS
    @given(soup=st.lists(st.sampled_from(words), max_size=soup_size))
    def test_word_soup_inside_a_program(soup, tmp_path_factory):
        read(program(" ".join(soup)).encode("utf-8", "replace"), tmp_path_factory.mktemp("f"))

    @SETTINGS
    @given(cut=st.integers(0, len(golden)), spliced=st.lists(st.sampled_from(words), max_size=12))
    def test_a_written_program_with_words_spliced_in(cut, spliced, tmp_path_factory):
        read(golden[:cut] + " ".join(spliced).encode() + golden[cut:], tmp_path_factory.mktemp("f"))

    return test_random_bytes, test_word_soup_inside_a_program, test_a_written_program_with_words_spliced_in
