"""The data declarations: netCDF variables (:mod:`.variables`), self-describing files written atomically
and verified when read (:mod:`.io`, :mod:`.appending`), and provenance (:mod:`.provenance`)."""
