"""Shared foundations: errors, budgets, file I/O, the output-folder guard, runtime settings."""
