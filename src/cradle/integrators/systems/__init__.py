"""What the compiled integrators integrate: one ``typing.NamedTuple`` per equation, with its right-hand side
and invariants registered for the generic operations of :mod:`cradle.integrators._dop853` (``rhs``,
``monitor``).

* :mod:`.lattice`: (nc)/(meca) and the damped (ncdamped);
* :mod:`.imperfect`: the imperfect cradle (ncimperfect), its right-hand side composed of the term units of
  :mod:`cradle.integrators.terms`, with or without damping;
* :mod:`.dps`: the DpS right-hand side family, (dfnls), (dpsdamped) and (dpsimperfect), one loop.
"""
