"""The plumbing, the top layer: config.yaml loaded into typed specs (:mod:`.config`), the results layout
(:mod:`.layout`), the outputs opened by name (:mod:`.outputs`), a scene's job (:mod:`.scene_job`) and the
runner that writes every output safely (:mod:`.runner`), cost estimates (:mod:`.budget`), code dependencies
of the rules (:mod:`.codedeps`), continuing runs (:mod:`.extend`) and the command line (:mod:`.cli`)."""
