"""Diyaroglu, Oterkus & Oterkus: an Euler–Bernoulli beam in ordinary state-based peridynamics (model ``pd-eb``).

C. Diyaroglu, E. Oterkus, S. Oterkus, "An Euler–Bernoulli beam formulation in an ordinary state-based
peridynamic framework", Mathematics and Mechanics of Solids 24(2) (2019) 361–376, doi:10.1177/1081286517728424
(docs/references.md). One transverse unknown w per point; the PD curvature, fictitious boundary layers and
master–slave end conditions. docs/models/diyaroglu.md is the guide.

==================  ===========================================================  ===============================
equation            what                                                         implemented by
==================  ===========================================================  ===============================
Eq. 2, 10a, 11a     PD curvature kappa_k = d Σ_j (w_{k+j} + w_{k-j} - 2 w_k)     ``operator.curvature_weights``,
                    / xi_j, d = 1/(A delta)                                      ``operator.curvature_operator``
Eq. 13–15           equation of motion (the Euler–Lagrange equations of the      ``model.PDEulerBernoulli``
                    energy a kappa^2 / 2)                                        (``form = direct``)
Eq. 15 + damping    explicit central differences                                 ``transient.simulate_eb``
Eq. 25              a point moment as a couple of line loads                     :func:`pdverify.numerics.loads
                                                                                 .body_loads`
Eq. 32–33           delta = (m + 0.015) dx, the calibration of a                 ``operator.curvature_weights``
Eq. 37–42           fictitious layers and the master–slave end conditions        ``operator.paper_system``,
                    (clamped, simply supported, free: Appendix A1–A12)           ``operator.paper_curvature``,
                                                                                 ``operator.mirror_map``,
                                                                                 ``operator.fictitious_curvature``
==================  ===========================================================  ===============================
"""

from .model import MODELS

__all__ = ["MODELS"]
