"""The core layer: what every other layer speaks. A scene (:mod:`.scene`, read by :mod:`.scene_file`), its axis
(:mod:`.geometry`), the result of a solve (:mod:`.result`), the model contract (:mod:`.contract`), the errors
that reach the user (:mod:`.errors`), support reactions from statics (:mod:`.reactions`) and the version.
Imports nothing of pdverify outside this package."""
