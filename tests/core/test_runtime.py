"""Process settings: the collector spares what a command's imports made, and gets it back."""

from __future__ import annotations

import gc

from coatsim.core.runtime import keep_frozen, long_lived_imports


def test_imports_run_without_the_collector_then_stay_out_of_its_passes_until_the_work_ends():
    assert gc.isenabled()
    with long_lived_imports():
        assert not gc.isenabled()
        made = [[]]  # an object made while importing
    assert gc.isenabled()
    assert gc.get_freeze_count() > 0
    with keep_frozen():
        assert gc.get_freeze_count() > 0
    assert gc.get_freeze_count() == 0
    assert made
