"""The plumbing: the typed config (:mod:`.config`), the results layout (:mod:`.layout`), code
dependencies of the rules (:mod:`.codedeps`), cost estimates (:mod:`.budget`), the stages
(:mod:`.stages`) and their runner (:mod:`.runner`), self-describing netCDF (:mod:`.io`,
:mod:`.variables`, :mod:`.provenance`), continuing runs (:mod:`.extend`) and the command line
(:mod:`.cli`)."""
