"""Moyer & Miraglia: micro-elastic peridynamic rod and Timoshenko beam, with dynamics (models ``pd-rod``,
``pd-timoshenko``, ``pd-torsion``).

E. T. Moyer, M. J. Miraglia, "Peridynamic solutions for Timoshenko beams", Engineering 6 (2014) 304–317,
doi:10.4236/eng.2014.66034 (docs/references.md). Bond integrals of the axial displacement, the deflection and the
rotation, Taylor ghost points beyond the ends, damped leapfrog velocity-Verlet in time; the torsion bar is the
rod's equation for the twist. docs/models/moyer.md is the guide.

================  ===============================================================  ================================
equation          what                                                             implemented by
================  ===============================================================  ================================
Eq. 1–3, 13–19    the rod's bond integral I_i = Σ_j c_j (u_{i+j} + u_{i-j} - 2u_i)  ``kernels.rod_kernel``,
                                                                                   ``operator.rod_operator``
Eq. 20–21, 53     Taylor ghost points (first or second order, from the first four  ``kernels.taylor_rows``
                  real points)
Eq. 19 (ends)     the corrected rod ends: mirror images of held and loaded ends    ``ends.rod_mirror_ghosts``
                  in place of Eq. 20–21's ghosts
Eq. 54–56         the torsion bar: the rod's bond integral for the twist θ, GJ     ``operator.rod_operator``
                  for EA (Section 5)                                               (``kind = "torsion"``)
Eq. 33–35         the beam's energy and its equations of motion                    ``operator.beam_operator``
Eq. 45–50         the beam's bending and shear integrals (the shear's principal    ``kernels.shear_kernel``,
                  value, Eq. 47; the J sum, Eq. 48)                                ``operator._beam_core``
Eq. 48 (energy)   the corrected beam as the gradient of a discrete energy          ``energy.energy_beam_operator``
Eq. 7–12, 36–44   damped leapfrog velocity-Verlet from rest                        ``transient.integrate``,
                                                                                   ``steps``
================  ===============================================================  ================================
"""

from .model import MODELS

__all__ = ["MODELS"]
