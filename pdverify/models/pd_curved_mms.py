"""Model ``pd-curved-mms``: ``pd-curved`` with the loads of the manufactured solution
(pdverify/manufactured.py) added through its ``body`` hook, so a study can run the quintic example with
one command (reference ``exact-curved-manufactured``, with the same ``fields``). Same options and
discretisation as pd-curved, plus ``fields``: ``trig`` (membrane strains O(U/L): loads ~ EA, kGA) or ``bending``
(membrane and shear strains O(h²/L²) of the bending ones, as a slender beam's: loads ~ EI, for locking
studies)."""

from __future__ import annotations

from ..manufactured import FIELDS
from ..registry import System
from ..result import Result
from ..scene import Scene
from .pd_curved import PDCurved


class PDCurvedMMS(PDCurved):
    name = "pd-curved-mms"
    bench_scene = "paper_curved/quintic_manufactured.toml"  # its loads come from the manufactured fields
    title = "pd-curved + manufactured loads (quintic example)"
    source = "pd-curved; loads by sympy from the chosen fields (pdverify/manufactured.py)"
    reference = True  # a verification harness, not a candidate model for `pdverify advise`
    options = PDCurved.options + (FIELDS,)

    def check(self, scene: Scene) -> list[str]:
        from ..exact.manufactured import manufactured_checks

        return super().check(scene) + manufactured_checks(scene)

    def solve(self, scene: Scene, params: dict, body=None) -> Result:
        from ..manufactured import body as mms_body

        return super().solve(scene, params, body=mms_body(scene, params.get("fields", "trig")))

    def assemble(self, scene: Scene, params: dict, body=None) -> System:
        """pd-curved's system with the manufactured loads added (what ``solve`` factorises)."""
        from ..manufactured import body as mms_body

        return super().assemble(scene, params, mms_body(scene, params.get("fields", "trig")) if body is None else body)


MODELS = [PDCurvedMMS()]
