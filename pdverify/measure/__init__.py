"""The measurement layer: error metrics and observed orders (:mod:`.metrics`), a case's trust status from the
round-off bounds (:mod:`.status`), natural frequencies against the analytic ones (:mod:`.modes`) and the memory
a solve will need (:mod:`.memory`). Reads results; builds on the registry."""
