"""The applications: the command line (:mod:`.cli`), the advisor (:mod:`.advise`), the benchmark (:mod:`.bench`),
the pipeline a study runs through (:mod:`.pipeline`: study, cards, JUnit, report, exit status) and the goldens'
regeneration (:mod:`.golden`). Nothing below imports them."""
