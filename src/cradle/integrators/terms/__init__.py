"""The terms of the imperfect cradle (ncimperfect) as compiled units, one module each.

Each unit declares, in its module: which declared parameters it takes (the config classes of
:mod:`cradle.models`, e.g. :class:`cradle.models.onsite.OnSite`) and the compiled ``typing.NamedTuple`` they
become (its ``build``); its force on the lattice (the operations of :mod:`.slots` it implements); its energy or
dissipation; and its DpS counterpart (what it becomes in (dpsimperfect) or (dpsdamped), see
:mod:`cradle.integrators.systems.dps`).

* :mod:`.hertz`: Hertz's contact (vhertz) between touching beads (the paper's contact law);
* :mod:`.precompression`: a static overlap delta_n (or a gap) of every contact;
* :mod:`.inhomogeneity`: bead masses m_n, on-site frequencies omega_n, contact stiffnesses k_n;
* :mod:`.onsite_harmonic`, :mod:`.onsite_quartic`, :mod:`.onsite_pendulum`: the on-site potential W;
* :mod:`.onsite_damping`: linear damping -gamma m_n v_n;
* :mod:`.contact_damping`: Kuwabara-Kono viscoelastic contact damping eta c^(alpha-1) c'.

Each slot of the right-hand side (:mod:`cradle.integrators.systems.imperfect`: contact law, sites, on-site
potential, on-site damping, contact damping) holds one unit, or the slot's *absent* unit (no arithmetic at
all): numba compiles the right-hand side once per combination a run uses (:mod:`cradle.integrators._generic`).
"""
