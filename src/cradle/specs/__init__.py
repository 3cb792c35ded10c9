"""Typed specs: the frozen dataclasses that declare every parameter of a run or an analysis, validated once."""
