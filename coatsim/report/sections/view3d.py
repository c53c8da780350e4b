"""The view3d section: the interactive 3-D view of every variant's thickness on the part and its
tool path (:mod:`coatsim.report.viewer`), the part drawn once; and the MP4 of the cell during the
run when one was made (``coatsim run --video``: rendering the arm costs more than the rest of
the report, so it is made on request only)."""

from __future__ import annotations

from typing import Any, Optional

from coatsim.report.html import Section, esc
from coatsim.report.viewer import viewer_html


def section(data: Any, video: Optional[str] = None) -> Section:
    body = viewer_html(data)
    if video:
        body += (f'<p>Video of the cell during the {esc(data.reference.name)} run: <a href="{esc(video)}">{esc(video)}'
                 "</a> (beside this report).</p>")
    else:
        body += ('<p class="muted">The arm and the part together: <code>coatsim run --video</code> renders the cell '
                 "during the run as an MP4 beside this report.</p>")
    body += ('<p class="muted">Each variant\'s full-resolution mesh with these colours and its tool path is in '
             "<code>VARIANT.thickness.glb</code> beside this report (any glTF viewer).</p>")
    return Section("view3d", "The coated part in 3-D", body)
