"""Fixtures of the programs-stage tests."""

from __future__ import annotations

import pytest

from coatsim.geometry.polysegment import Polysegment
from program_helpers import roundrect


@pytest.fixture
def rr() -> Polysegment:
    """The exact 150 x 80 mm rounded rectangle (10 mm radii), centred on the origin."""
    return roundrect()
