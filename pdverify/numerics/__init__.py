"""The numerics layer: banded matrices (:mod:`.band`), linear solves with round-off bounds (:mod:`.linalg`),
PD families and stencil operators (:mod:`.families`), Taylor ghost points (:mod:`.ghosts`), loads on a point
grid (:mod:`.loads`) and their warnings (:mod:`.load_warnings`), the energy ledger of explicit time integration
(:mod:`.timeint`) and dispersion relations (:mod:`.dispersion`). Pure functions of arrays; imports only
:mod:`pdverify.core`."""
