"""`coatsim run --video`: an MP4 of the polysegment run, linked from the report (slow: it renders
every frame)."""

from __future__ import annotations

import contextlib
import io
import sys
from pathlib import Path

import pytest
from small_scenario import SMALL

from coatsim import cli


@pytest.mark.slow
def test_video_is_an_mp4_of_the_spray_time_linked_from_the_report(tmp_path: Path) -> None:
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    from coatsim.report.video import FPS, LEAD_S

    scenario = tmp_path / "job.yaml"
    scenario.write_text(SMALL.replace("gates:", "variants: [polysegment, polyline-blend]\ngates:").replace(
        '  - {metric: coating.thickness_cv, op: "<", threshold: 0.0}\n', ""), encoding="utf-8")
    old, out = sys.argv, io.StringIO()
    sys.argv = ["coatsim", "run", str(scenario), "--fast", "--video", "-o", str(tmp_path / "out")]
    try:
        with contextlib.redirect_stdout(out), pytest.raises(SystemExit) as info:
            cli.main()
    finally:
        sys.argv = old
    assert (info.value.code or 0) == 0, out.getvalue()
    movie = tmp_path / "out" / "polysegment.mp4"
    reader = imageio_ffmpeg.read_frames(str(movie))
    meta = reader.__next__()
    frames = sum(1 for _ in reader)
    assert meta["size"] == (640, 420) and meta["fps"] == pytest.approx(FPS)
    import json

    motion = json.loads((tmp_path / "out" / "metrics.json").read_text())["variants"]["polysegment"]["motion"]
    assert frames >= FPS * (motion["cycle_time_s"] + 2 * LEAD_S) * 0.9
    assert 'href="polysegment.mp4"' in (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    assert not list((tmp_path / "out").glob(".*.tmp"))
