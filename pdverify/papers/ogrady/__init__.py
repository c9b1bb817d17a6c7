"""O'Grady & Foster: a non-ordinary state-based bond-pair (rotational spring) beam (model ``pd-bond-pair``).

J. O'Grady, J. Foster, "Peridynamic beams: a non-ordinary, state-based model", International Journal of Solids
and Structures 51(18) (2014) 3177–3183, doi:10.1016/j.ijsolstr.2014.05.014; LaTeX source
github.com/johntfoster/BeamPaper (docs/references.md). Each pair of collinear bonds is a rotational spring; its
energy is Eq. 2, its small-rotation form the bond-pair stencil. docs/models/ogrady.md is the guide.

================  ===========================================================  ====================================
equation          what                                                         implemented by
================  ===========================================================  ====================================
Eq. 1–2           the bond-pair energy, the angle between the bonds            ``nonlinear.NonlinearBondPair``
                                                                               (large rotations)
Eq. 2, small      the linear stencil Σ_j c_j (w_{k+2j} - 4 w_{k+j} + 6 w_k     ``taylor``, ``pairs`` (phi = D w)
rotations         - 4 w_{k-j} + w_{k-2j}); the pairs' deviations phi = D w
Eq. 5, §3.1       alpha on the discrete family sum, EI / Σ omega xi^2 dx       ``calibration.alpha``
                  (``variant = paper``: whole nodes; ``corrected``: the
                  cells' parts); 3 EI / delta^3 a reconstruction
                  (``continuous-alpha``)
Eq. 6             the section weight omega = |xi| b(y), y = (xi / delta) c;    ``weights.weights``
                  the fibre weight omega = b(y)
Eq. 7             elastic-perfectly plastic pairs: capped force, critical      ``path``
                  angle delta eps_y / c, plastic offsets
Eq. 8, §3.2       brittle pairs broken for good, the most deformed first;      ``path``
                  node health
ends              mirror (reflection) images and the axial condition           ``ends``, ``pairs.ghost_rows``
Eq. 5, omega = 1  no limit at fixed delta where one point carries a force       ``limit``
                  (the symbol grows like |k|)
================  ===========================================================  ====================================
"""

from .model import MODELS

__all__ = ["MODELS"]
