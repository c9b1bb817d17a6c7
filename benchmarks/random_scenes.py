"""Random scenes through the models: what a new user's odd but valid input does (docs/trust.md, "Random scenes").

    PYTHONPATH=. python benchmarks/random_scenes.py --seed 1 --count 300

Each scene draws a length (1 µm to 100 km), a square section from L/3 to L/10^4, a material (E = 1 to 1e15 Pa,
Poisson's ratio 0 to 0.499), end supports (a spring now and then, an inner support now and then), one to three loads
anywhere, on the ends and on the supports included, and now and then an arc axis (``--rich``: also rotational springs,
a second support inside and a stiffer segment now and then). Two findings:

* ``crash``: ``pdverify solve`` (in this process, the CLI's own entry point) ends other than with 0, 2 (bad input)
  or 3 (a failed computation), or prints a traceback;
* ``silent``: a model with an exact reference of its theory (``exact_reference``) solves the scene without a warning
  and its deflection (the rod's u, the bar's twist) is more than ``--limit`` (default 2 %) from the reference's,
  relative to the reference's largest, where that is above 1e-12 of the scene's scale.

Same seed, same scenes. Prints one line per finding and the counts; exit 1 when there is a finding.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import random
import sys
import tempfile
import traceback
from pathlib import Path

import numpy as np

from pdverify.apps.cli import main as cli_main
from pdverify.core.errors import PdverifyError
from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run
from pdverify.study.reference import measured
from pdverify.verify.suite import exact_reference, toml_text

SUPPORTS = ["clamped", "pinned", "roller", "free", "guided"]
JUDGED = "pd-eb pd-bond-pair pd-timoshenko pd-higher-order pd-rod pd-torsion fem-eb fem-timoshenko".split()
CLI_MODELS = JUDGED + "pd-curved exact-eb exact-timoshenko exact-higher-order exact-curved exact-rod".split()
CLI_MODELS.append("exact-torsion")


def magnitude(rng: random.Random) -> float:
    return rng.choice([1.0, 0.3, 2.5, 1e-6, 1e6, 1e-3, 1e3, 7.7, 0.05])


def load(rng: random.Random, length: float) -> dict:
    kind = rng.choice(["force", "axial", "moment", "torque", "uniform", "partial", "sine"])
    at = length * rng.choice([0.0, 0.5, 0.3333333, 1.0, 0.999999, 0.0001, 0.25])
    if kind == "force":
        return {"type": "point_force", "position": at, "value": magnitude(rng) * rng.choice([1, -1])}
    if kind == "axial":
        return {"type": "point_force", "position": at, "value": 0.0, "axial": magnitude(rng)}
    if kind == "moment":
        return {"type": "point_moment", "position": at, "value": magnitude(rng)}
    if kind == "torque":
        return {"type": "point_torque", "position": at, "value": magnitude(rng)}
    if kind == "partial":
        a, b = sorted([length * rng.random(), length * rng.random()])
        return {"type": "distributed", "value": -magnitude(rng), "start": a, "end": b}
    return {"type": "distributed", "value": magnitude(rng), **({"shape": "sine"} if kind == "sine" else {})}


RICH = False  # --rich: also rotational springs, a second support inside and a stiffer segment now and then


def scene(rng: random.Random, curved: bool = True) -> dict:
    length = rng.choice([1.0, 2.0, 1e-6, 1e3, 0.37, 1e5])
    supports: dict = {"left": rng.choice(SUPPORTS), "right": rng.choice(SUPPORTS)}
    if rng.random() < 0.25:
        supports["inner"] = [
            {"position": length * rng.choice([0.5, 0.3, 0.71]), "type": rng.choice(["pinned", "roller", "clamped"])}
        ]
    if rng.random() < 0.1:
        supports["right"] = {"type": "spring", "stiffness": magnitude(rng) * 1e5}
    if RICH and rng.random() < 0.3:
        supports["right"] = {
            "type": "spring",
            "stiffness": magnitude(rng) * 1e5,
            "rotational_stiffness": magnitude(rng) * 1e3,
        }
    if RICH and rng.random() < 0.3:
        supports["inner"] = supports.get("inner", []) + [
            {"position": length * rng.choice([0.15, 0.62, 0.9]), "type": rng.choice(["pinned", "clamped"])}
        ]
    h = length / rng.choice([3, 5, 20, 100, 1e4])
    d = {
        "name": "random scene",
        "beam": {"length": length},
        "section": {"width": h, "height": h},
        "material": {
            "youngs_modulus": rng.choice([70e9, 1.0, 1e15, 2e11]),
            "poissons_ratio": rng.choice([0.3, 0.0, 0.49, 0.499]),
        },
        "supports": supports,
        "loads": [load(rng, length) for _ in range(rng.randint(1, 3))],
    }
    if RICH and rng.random() < 0.25:
        cut = length * rng.choice([0.4, 0.55])
        d["segments"] = [
            {"start": 0.0, "end": cut},
            {"start": cut, "end": length, "section": {"width": 1.5 * h, "height": 1.5 * h}},
        ]
    if curved and rng.random() < 0.15 and "segments" not in d:
        d["axis"] = rng.choice(
            [
                {"type": "arc", "radius": length / np.pi, "start_angle_deg": 180.0, "end_angle_deg": 0.0},
                {"type": "arc", "radius": 2 * length / np.pi, "start_angle_deg": 0.0, "end_angle_deg": 90.0},
            ]
        )
    return d


def crash(rng: random.Random, folder: Path, i: int) -> str | None:
    """The one line of a finding of ``pdverify solve`` on a random scene, or None."""
    path = folder / f"scene{i}.toml"
    drawn = scene(rng)
    path.write_text(toml_text(drawn))
    args = ["solve", str(path), "-m", rng.choice(CLI_MODELS), "--points", str(rng.choice([3, 11, 41, 101, 201, 1001]))]
    args += ["--format", rng.choice(["table", "csv", "json"])]
    args += ["--horizon", str(rng.choice([1, 2, 3, 5.5, 0.5]))] if rng.random() < 0.3 else []
    args += ["--estimate"] if rng.random() < 0.2 else []
    err = io.StringIO()
    try:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            cli_main(args)
        code = 0
    except SystemExit as exc:
        code = exc.code
    except Exception:  # noqa: BLE001 - the finding itself
        code, _ = "exception", err.write(traceback.format_exc())
    text = err.getvalue()
    if code in (0, 2, 3) and "Traceback" not in text:
        return None
    last = (text.strip().splitlines() or [""])[-1][:200]
    return f"crash: {' '.join(args[1:])}: exit {code}: {last}; scene {json.dumps(drawn)}"


def silent(rng: random.Random, limit: float) -> tuple[bool, str | None]:
    """(judged, the one line of a finding or None): a model without a warning far from its exact reference."""
    d = scene(rng, curved=False)
    name = rng.choice(JUDGED)
    model = get_model(name)
    try:
        sc = parse_scene(d)
    except PdverifyError:
        return False, None
    reference = exact_reference(model, {})
    if model.check(sc) or reference is None:
        return False, None
    ref_name = reference if isinstance(reference, str) else reference["model"]
    ref_opts = {} if isinstance(reference, str) else {k: v for k, v in reference.items() if k != "model"}
    n = rng.choice([101, 201, 401])
    exact = get_model(ref_name)
    try:
        got = run(sc, name, points=n)
        run(sc, ref_name, points=n, **ref_opts)  # its checks (a mechanism, a scene it refuses), as a study's
        fields = exact.evaluator(sc, exact.resolve(sc, ref_opts))(got.x)  # exact at the model's own points
    except PdverifyError:
        return False, None
    q = "w" if model.bending else ("u" if model.axial else "twist")
    a, b = np.asarray(got.measured(q)), measured(fields, q, ref_name)
    top = np.abs(b).max()
    if top <= 1e-9 * deflection_scale(sc):  # nothing moves: every load on the supports
        return False, None
    err = float(np.abs(a - b).max() / top)
    if err <= limit or got.info.get("warnings"):
        return True, None
    loads = [(ld["type"], round(ld.get("position", -1.0) / sc.length, 6)) for ld in d["loads"]]
    return True, (
        f"silent: {name} at {n} points, {err:.2e} from {ref_name}: supports {d['supports']}, loads {loads}; "
        f"scene {json.dumps(d)}"
    )


def deflection_scale(sc) -> float:
    """The size of the scene's deflections: each load's cantilever deflection summed (P L^3 + M L^2 + q L^4) / EI,
    the rod's and the bar's with EA and GJ, and the softest spring's give under the loads' resultant."""
    L, (E, G), sec = sc.length, (sc.material.E, sc.material.G), sc.section
    total = 0.0
    for ld in sc.loads:
        if ld.type == "distributed":
            q = abs(ld.value) * L**4 / (E * sec.I) + abs(getattr(ld, "axial", 0.0) or 0.0) * L**2 / (E * sec.A)
            total += q + abs(getattr(ld, "torque", 0.0) or 0.0) * L**2 / (G * sec.J)
        elif ld.type == "point_force":
            total += abs(ld.value) * L**3 / (E * sec.I) + abs(ld.axial or 0.0) * L / (E * sec.A)
        elif ld.type == "point_moment":
            total += abs(ld.value) * L**2 / (E * sec.I)
        elif ld.type == "point_torque":
            total += abs(ld.value) * L / (G * sec.J)
    springs = [s.stiffness for s in (sc.supports.left, sc.supports.right) if not isinstance(s, str) and s.stiffness]
    springs += [s.stiffness for s in sc.supports.inner if s.type == "spring" and s.stiffness]
    if springs:  # a spring's own give under the loads' resultant
        force = sum(abs(ld.value) for ld in sc.loads if ld.type == "point_force")
        force += sum(abs(ld.value) * L for ld in sc.loads if ld.type == "distributed")
        total += force / min(springs)
    return total


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--count", type=int, default=300, help="scenes of each kind (CLI runs, judged solves)")
    p.add_argument("--limit", type=float, default=0.02)
    p.add_argument("--rich", action="store_true", help="also rotational springs, two supports inside, segments")
    args = p.parse_args(argv)
    global RICH
    RICH = args.rich
    rng = random.Random(args.seed)
    findings, judged = [], 0
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.count):
            line = crash(rng, Path(tmp), i)
            findings += [line] if line else []
    for _ in range(args.count):
        was_judged, line = silent(rng, args.limit)
        judged += was_judged
        findings += [line] if line else []
    for line in findings:
        print(line)
    print(f"{args.count} CLI runs, {judged} judged solves: {len(findings)} finding(s)")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
