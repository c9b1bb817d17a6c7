"""Off-screen PNG of a plane-stress result (deformed mesh coloured by the nodal von Mises stress) with pyvista:
the colour bar is horizontal under the beam with its title and unit, the displacement scale factor is written
in the picture.

Rendering runs in a subprocess so that a crashing OpenGL backend cannot take the solver down; without a
display VTK falls back to its off-screen (EGL/OSMesa) context. One such process per solving process draws every
picture that process asks for, one request per line (starting pyvista and its context costs about 1.4 s, a
picture about 0.15 s); it ends when its parent does (its input closes). ``render_png`` raises a clear error if
the picture fails or the process dies, and the VTU output is unaffected; the next picture starts a new process.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

from pdverify.core.errors import SolveError

_SCRIPT = r"""
import json, sys, traceback
import pyvista as pv
pv.OFF_SCREEN = True

def draw(vtu, png, scale):
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
    p.close()

for line in sys.stdin:
    job = json.loads(line)
    try:
        draw(job["vtu"], job["png"], float(job["scale"]))
        reply = {"ok": True}
    except Exception as exc:
        reply = {"ok": False, "error": (traceback.format_exception_only(exc)[-1]).strip()}
    print(json.dumps(reply), flush=True)
"""

TIMEOUT_S = 120  # one picture, the renderer's start included


class _Renderer:
    """The drawing process of this process: started at the first picture, again after a failure."""

    proc: subprocess.Popen | None = None
    owner = 0  # the pid that started it (a forked child starts its own)
    errors = None  # its stderr: a file, not a pipe that a chatty VTK could fill

    @classmethod
    def draw(cls, vtu_path: str, png_path: str, scale: float) -> dict:
        if cls.proc is None or cls.owner != os.getpid() or cls.proc.poll() is not None:
            cls.errors = tempfile.TemporaryFile("w+")
            cls.proc = subprocess.Popen(
                [sys.executable, "-c", _SCRIPT],
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=cls.errors,
                text=True,
            )
            cls.owner = os.getpid()
        proc = cls.proc
        try:
            proc.stdin.write(json.dumps({"vtu": vtu_path, "png": png_path, "scale": scale}) + "\n")
            proc.stdin.flush()
            line = _read_line(proc, TIMEOUT_S)
        except (OSError, ValueError, TimeoutError) as exc:
            line = ""
            err = str(exc) or type(exc).__name__
        else:
            err = ""
        if not line:  # it died or hung: end it, say why; the next picture starts another
            proc.kill()
            proc.wait()
            cls.errors.seek(0)
            tail = cls.errors.read().strip().splitlines()
            cls.proc = None
            return {"ok": False, "error": (tail or [err or "no message"])[-1]}
        return json.loads(line)


def _read_line(proc: subprocess.Popen, timeout: float) -> str:
    """The renderer's next reply line ('' when it ended); TimeoutError after ``timeout`` seconds."""
    import selectors

    with selectors.DefaultSelector() as sel:
        sel.register(proc.stdout, selectors.EVENT_READ)
        if not sel.select(timeout):
            raise TimeoutError(f"no picture after {timeout:g} s")
    return proc.stdout.readline()


def render_png(vtu_path: str, png_path: str, scale: float) -> None:
    reply = _Renderer.draw(vtu_path, png_path, float(scale))
    if not reply.get("ok"):
        raise SolveError(
            f"{png_path}: off-screen rendering failed ({reply.get('error', 'no message')}); "
            "the VTU file is still written"
        )
