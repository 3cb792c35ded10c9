"""Measurements on runs: the approximate solution (ansatz), E(t) and spectra on Gamma*
(:mod:`.compare`), sideband ratios and carrier shares (:mod:`.sidebands`), breather periods,
peak compressions and merging times (:mod:`.breathers`), the desk-toy experiments: one out one out, the
line's break-up, energy per bead per swing (:mod:`.desk_toy`)."""
