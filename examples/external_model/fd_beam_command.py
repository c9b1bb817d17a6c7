"""An external pdverify model: reads {"model", "scene", "options"} as JSON on stdin, writes {"x", "w", ...} on
stdout. It does not import pdverify: the scene arrives as plain JSON (beam.length, section, material,
supports.left/right, loads[] with type, value, position or start/end/shape), so any language works the same
way. This one is Python and uses the finite-difference solver of the example plug-in (fd_beam/fd.py, numpy and
scipy only), loaded as a file."""

import importlib.util
import json
import sys
import time
from pathlib import Path

spec = importlib.util.spec_from_file_location(
    "fd", Path(__file__).resolve().parents[1] / "plugin_model" / "src" / "fd_beam" / "fd.py"
)
fd = importlib.util.module_from_spec(spec)
spec.loader.exec_module(fd)

job = json.load(sys.stdin)
t0 = time.perf_counter()
result = fd.solve(job["scene"], int(job["options"]["points"]))
json.dump(
    {
        "x": result["x"].tolist(),
        "w": result["w"].tolist(),
        "rotation": result["rotation"].tolist(),
        "fields": {"M": result["M"].tolist()},
        "timings": {"solve_s": time.perf_counter() - t0},
    },
    sys.stdout,
)
