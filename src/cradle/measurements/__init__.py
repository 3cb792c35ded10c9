"""Measurements on runs: the approximate solution (ansatz), E(t) and spectra on Gamma*
(:mod:`.compare`), sideband ratios and carrier shares (:mod:`.sidebands`), breather periods,
peak compressions and merging times (:mod:`.breathers`)."""
