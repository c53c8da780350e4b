"""The robot languages coatsim writes and reads, by name."""

from __future__ import annotations

from coatsim.languages.kawasaki_as.dialect import KAWASAKI_AS
from coatsim.path.dialect import Dialect

LANGUAGES: dict[str, Dialect] = {KAWASAKI_AS.name: KAWASAKI_AS}
