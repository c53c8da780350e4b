"""Puts the helpers shared by the language tests (language_plans.py) on the import path."""
