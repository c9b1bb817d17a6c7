"""Yang, Oterkus & Oterkus: a peridynamic higher-order beam (model ``pd-higher-order``).

Z. Yang, E. Oterkus, S. Oterkus, "Peridynamic higher-order beam formulation", Journal of Peridynamics and
Nonlocal Modeling (2020), doi:10.1007/s42102-020-00043-w (docs/references.md). Four unknowns per point, theta,
theta*, w, w* (u = z theta + z^3 theta*, w = w + z^2 w*); five bond measures; Appendix B's mirror images at the
ends. The local theory it discretises is :mod:`pdverify.theory.higher_order`, which ``exact-higher-order``
solves exactly. docs/models/yang.md is the guide.

==============  ======================================================================  =============================
equation        what                                                                    implemented by
==============  ======================================================================  =============================
Eq. 2–3, 9      kinematics and the energy density Q = m^T C m                           :mod:`pdverify.theory
                                                                                        .higher_order`
Eq. 13–15       the PD energy over bonds and its Hessian (the stiffness)                ``bonds.energy``,
                                                                                        ``bonds.assemble_blocks``,
                                                                                        ``operator.band_operator``
Eq. 14a–f       the five bond measures and the bond weights                             ``bonds.bond_measures``,
                                                                                        ``bonds.bond_weights``
Eq. 16a–b       body forces and the load vector                                         ``ends.load_vector``
Eq. 4b, 6a–c    stresses through the section                                            ``outputs``
Eq. B39–B41     mirror images of clamped, simply supported and free ends                ``ends.mirror_map``,
                                                                                        ``ends.end_conditions``
==============  ======================================================================  =============================
"""

from .model import MODELS

__all__ = ["MODELS"]
