"""Typed specs: the frozen dataclasses that declare every parameter of a run or an analysis
(:mod:`.declare` the declaration helpers and
the shared parameter types). Built and validated once; the science
takes them and trusts them."""
