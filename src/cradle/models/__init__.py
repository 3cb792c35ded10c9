"""The paper's objects: the lattice (nc) with the Hertz potential (vhertz) and energy (ham)
(:mod:`.lattice`), the DpS equation (dfnls) and its plane waves (ansatz3)/(freq) (:mod:`.dps`),
the stationary problem (dpsstn) and the map G (comp1)-(comp2) (:mod:`.stationary`), its
homoclinic solutions (:mod:`.homoclinic`, :mod:`.homoclinic_tails`,
:mod:`.homoclinic_continuation`), the exact travelling waves of (ad) (:mod:`.waves`) and the
initial data (ansatzapprox)/(perturb)/(ansatzapproxst2) (:mod:`.initial`), the map between a real
cradle and the dimensionless variables of (nc) (:mod:`.physical`), the desk-toy experiments' released state
(:mod:`.desk_toy`) and the ideal hard-sphere cradle beside which they are measured (:mod:`.hard_spheres`)."""
