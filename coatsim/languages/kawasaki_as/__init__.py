"""Kawasaki AS as real cells use it: source decoding, lexer, parser into a typed syntax tree,
expressions, interpreter to a ToolPath, writer, and the dialect object for the pipeline."""

from coatsim.languages.kawasaki_as.interpreter import MAX_STEPS, Run, interpret, interpret_run
from coatsim.languages.kawasaki_as.parser import parse_as, parse_as_bytes
from coatsim.languages.kawasaki_as.source import AsSyntaxError

__all__ = ["AsSyntaxError", "MAX_STEPS", "Run", "interpret", "interpret_run", "parse_as", "parse_as_bytes"]
