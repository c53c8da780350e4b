"""The package's entry points: each name in ``coatsim.__all__`` resolves, lazily, to the object its
module defines, and the API reference documents it."""

import subprocess
import sys
from pathlib import Path

import pytest

import coatsim

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("name", coatsim.__all__)
def test_entry_point_resolves_to_its_module(name: str) -> None:
    from importlib import import_module

    module = import_module(coatsim._ENTRY_POINTS[name])
    assert getattr(coatsim, name) is getattr(module, name)


def test_unknown_name_lists_the_entry_points() -> None:
    with pytest.raises(AttributeError, match="segment_curve"):
        coatsim.no_such_thing  # noqa: B018


def test_import_loads_no_stage() -> None:
    code = "import sys, coatsim; print(sorted(m for m in sys.modules if m.startswith('coatsim.')))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    assert out.stdout.strip() == "[]"


def test_api_reference_documents_every_entry_point() -> None:
    page = (ROOT / "docs" / "reference" / "api.md").read_text(encoding="utf-8")
    for name in coatsim.__all__:
        module = coatsim._ENTRY_POINTS[name]
        assert f"::: {module}" in page or f"::: {module}.{name}" in page, name
