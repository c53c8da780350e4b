"""KUKA KRL: a ``.src``/``.dat`` pair parsed, interpreted to a ToolPath and written; the
language object for the registry is in :mod:`.language`."""
