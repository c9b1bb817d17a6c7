"""An external pdverify model: reads {"scene", "options"} as JSON on stdin, writes {"x", "w", ...} on stdout.

Any language works the same way; this one is Python and solves with the fd-eb example plug-in's code.
"""

import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plugin_model" / "src"))

from fd_beam import FDBeam  # noqa: E402

from pdverify.scene import parse_scene  # noqa: E402

job = json.load(sys.stdin)
t0 = time.perf_counter()
result = FDBeam().solve(parse_scene(job["scene"]), job["options"])
json.dump(
    {
        "x": result.x.tolist(),
        "w": result.w.tolist(),
        "rotation": result.rotation.tolist(),
        "fields": {"M": result.fields["M"].tolist()},
        "timings": {"solve_s": time.perf_counter() - t0},
    },
    sys.stdout,
)
