"""Off-screen PNG of a plane-stress result (deformed mesh coloured by von Mises) with pyvista.

Rendering runs in a subprocess so that a crashing OpenGL backend cannot take the solver down; without a
display VTK falls back to its off-screen (EGL/OSMesa) context. ``render_png`` raises a clear error if the
subprocess fails, and the VTU output is unaffected.
"""

from __future__ import annotations

import subprocess
import sys

from pdverify.errors import SolveError

_SCRIPT = r"""
import sys
import pyvista as pv
pv.OFF_SCREEN = True
vtu, png, scale = sys.argv[1], sys.argv[2], float(sys.argv[3])
mesh = pv.read(vtu)
warped = mesh.warp_by_vector("displacement", factor=scale)
p = pv.Plotter(off_screen=True, window_size=(1200, 420))
p.add_mesh(mesh, style="wireframe", color="lightgray", opacity=0.5)
p.add_mesh(warped, scalars="von_mises", cmap="viridis", show_edges=True, scalar_bar_args={"title": "von Mises (Pa)"})
p.view_xy()
p.camera.zoom(1.3)
p.screenshot(png)
"""


def render_png(vtu_path: str, png_path: str, scale: float) -> None:
    proc = subprocess.run(
        [sys.executable, "-c", _SCRIPT, vtu_path, png_path, repr(float(scale))],
        capture_output=True,
        text=True,
        timeout=120,
    )
    if proc.returncode != 0:
        last = (proc.stderr.strip().splitlines() or ["no message"])[-1]
        raise SolveError(f"{png_path}: off-screen rendering failed ({last}); the VTU file is still written")
