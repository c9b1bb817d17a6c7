"""Off-screen PNG of a plane-stress result (deformed mesh coloured by the nodal von Mises stress) with pyvista:
the colour bar is horizontal under the beam with its title and unit, the displacement scale factor is written
in the picture.

Rendering runs in a subprocess so that a crashing OpenGL backend cannot take the solver down; without a
display VTK falls back to its off-screen (EGL/OSMesa) context. ``render_png`` raises a clear error if the
subprocess fails, and the VTU output is unaffected.
"""

from __future__ import annotations

import subprocess
import sys

from pdverify.core.errors import SolveError

_SCRIPT = r"""
import sys
import pyvista as pv
pv.OFF_SCREEN = True
vtu, png, scale = sys.argv[1], sys.argv[2], float(sys.argv[3])
mesh = pv.read(vtu)
warped = mesh.warp_by_vector("displacement", factor=scale)
p = pv.Plotter(off_screen=True, window_size=(1200, 520))
linear = int(mesh.celltypes.max()) == 9  # VTK_QUAD; quad8 / quad9 are drawn without their tessellation's edges
edges = dict(boundary_edges=True, feature_edges=False, manifold_edges=False, non_manifold_edges=False)
p.add_mesh(mesh.extract_feature_edges(**edges), color="gray", line_width=1)
bar = {"title": "von Mises stress (Pa)", "vertical": False, "position_x": 0.2, "position_y": 0.04, "width": 0.6,
       "height": 0.1, "title_font_size": 18, "label_font_size": 14, "fmt": "%.3g"}
p.add_mesh(warped, scalars="von_mises", cmap="viridis", show_edges=linear, scalar_bar_args=bar)
p.add_text(f"displacements drawn x {scale:.4g} (grey: undeformed)", position="upper_left", font_size=11)
p.view_xy()
p.camera.zoom(1.25)
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
