"""Robot languages: a registry of plug-ins, one package per language."""
