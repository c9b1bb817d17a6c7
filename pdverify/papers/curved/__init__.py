"""A peridynamic planar curved Timoshenko–Ehrenfest beam with peridynamic differential-operator functions
(models ``pd-curved`` and ``pd-curved-mms``).

"A peridynamic formulation for planar arbitrarily curved Timoshenko–Ehrenfest beams", Mathematics and Mechanics
of Solids (2024), doi:10.1177/10812865241269781 (docs/references.md; the equations as reconstructed in
docs/design/formulas.md). Three unknowns per particle (u_t, u_n, phi) along any planar axis; PDDO functions of
degree P replace the derivatives; collocation of the equilibrium equations. docs/models/curved.md is the guide.

==============  ===============================================================  ===================================
equation        what                                                             implemented by
==============  ===============================================================  ===================================
Eq. 3–4         strains and resultants N, Q, M of the curved axis                ``assembly.assemble_resultants``
Eq. 8–10        equilibrium of the curved beam                                   ``assembly.assemble_resultants``
Eq. 11–13       boundary conditions                                              ``assembly.conditions``
Eq. 14–16       the equilibrium in the displacements (the primal form)           ``assembly.assemble_displacements``
§3.2            PDDO functions of degree P                                       ``pddo``
Eq. 27–35       the collocation system                                           ``model.PDCurved.assemble_band``
==============  ===============================================================  ===================================

``pd-curved-mms`` (``mms.py``) adds the loads of the manufactured solution of
:mod:`pdverify.theory.curved_manufactured`.
"""

from .mms import MODELS as _MMS
from .model import MODELS as _MODELS

MODELS = [*_MODELS, *_MMS]

__all__ = ["MODELS"]
