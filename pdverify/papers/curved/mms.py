"""Model ``pd-curved-mms``: ``pd-curved`` with the loads of the manufactured solution
(:mod:`pdverify.theory.curved_manufactured`) added through its ``body`` hook, so a study can run the quintic
example with one command (reference ``exact-curved-manufactured``, with the same ``fields``). Same options and
discretisation as pd-curved, plus ``fields``: ``trig`` (membrane strains O(U/L): loads ~ EA, kGA) or ``bending``
(membrane and shear strains O(h²/L²) of the bending ones, as a slender beam's: loads ~ EI, for locking
studies)."""

from __future__ import annotations

from ...core.contract import System
from ...core.result import Result
from ...core.scene import Scene
from ...theory.curved_manufactured import FIELDS, manufactured_checks
from ...theory.curved_manufactured import body as mms_body
from .model import PDCurved


class PDCurvedMMS(PDCurved):
    name = "pd-curved-mms"
    bench_scene = "paper_curved/quintic_manufactured.toml"  # its loads come from the manufactured fields
    title = "pd-curved + manufactured loads (quintic example)"
    source = "pd-curved; loads by sympy from the chosen fields (:mod:`pdverify.theory.curved_manufactured`)"
    reference = True  # a verification harness, not a candidate model for `pdverify advise`
    options = PDCurved.options + (FIELDS,)
    springs = inner_supports = segments = False  # the manufactured fields hold on one uniform beam between its ends

    def check(self, scene: Scene) -> list[str]:
        return super().check(scene) + manufactured_checks(scene)

    def solve(self, scene: Scene, params: dict, body=None) -> Result:
        return super().solve(scene, params, body=mms_body(scene, params.get("fields", "trig")))

    def assemble(self, scene: Scene, params: dict, body=None) -> System:
        """pd-curved's system with the manufactured loads added (what ``solve`` factorises)."""
        return super().assemble(scene, params, mms_body(scene, params.get("fields", "trig")) if body is None else body)


MODELS = [PDCurvedMMS()]
