"""The sections of report.html, one module each, in the report's order (docs/formats.md, "Report
sections"): verdict, speed, thickness-along-track, maps, warnings, view3d, program, metrics, then
summary and gates (:mod:`.tables`). Each ``section(data)`` takes a
:class:`coatsim.report.data.ReportData` and returns a :class:`coatsim.report.html.Section`."""
