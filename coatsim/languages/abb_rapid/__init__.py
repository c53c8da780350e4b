"""ABB RAPID: modules (``.mod``, ``.modx``, ``.prg``, ``.sys``) parsed, interpreted to a
ToolPath and written; the language object for the registry is in :mod:`.language`."""
