"""Beyond the paper: each analysis declared in :mod:`.registry` (theorem1, mi-diagram, mi-growth,
mi-statistics, floquet), the work-precision of the integrators (:mod:`.work_precision`) and the
paper's claims against ours (:mod:`.paper_checks`)."""
