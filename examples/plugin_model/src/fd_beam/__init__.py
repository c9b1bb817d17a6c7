"""fd-eb: a pdverify plug-in. The model is a plain object following pdverify's contract: a name, its options
(``POINTS``: a grid), its theory, and ``solve(scene, params) -> Result``; the numerics are in ``fd.py``
(numpy/scipy on the scene's JSON form, shared with examples/external_model)."""

from pdverify.core.contract import POINTS, Model
from pdverify.core.result import Result

from . import fd


class FDBeam(Model):
    name = "fd-eb"
    title = "Euler-Bernoulli beam, central finite differences (example plug-in)"
    source = "examples/plugin_model"
    options = (POINTS,)
    theory = "euler-bernoulli"

    def solve(self, scene, params):
        n = params["points"]
        r = fd.solve(scene.to_dict(), n)
        return Result(scene.name, self.name, params, r["x"], r["w"], r["rotation"], {"M": r["M"]}, dofs=2 * n)
