"""Scenario runs: the schema, what a scenario reads, the pipeline and its typed results."""
