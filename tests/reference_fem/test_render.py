"""The plane-stress pictures: one drawing process per solving process, a failed picture one clear error."""

import os

import pytest
from helpers import ROOT

from pdverify.core.errors import SolveError
from pdverify.core.scene_file import load_scene
from pdverify.registry import run
from reference_fem import render


@pytest.mark.slow
def test_pictures_share_one_renderer_and_a_failure_is_one_error(tmp_path):
    result = run(load_scene(ROOT / "studies/paper_yang/cantilever_tip_force.toml"), "fem-plane-stress", points=21)
    result.writers[".png"](str(tmp_path / "a.png"))
    first = render._Renderer.proc
    result.writers[".png"](str(tmp_path / "b.png"))
    assert render._Renderer.proc is first and render._Renderer.owner == os.getpid()
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()  # the same picture, drawn alike
    with pytest.raises(SolveError, match="off-screen rendering failed .*the VTU file is still written"):
        render.render_png(str(tmp_path / "missing.vtu"), str(tmp_path / "c.png"), 1.0)
    result.writers[".png"](str(tmp_path / "d.png"))  # the renderer goes on after a failed picture
    assert (tmp_path / "d.png").read_bytes() == (tmp_path / "a.png").read_bytes()
