"""The command line of the estimate benchmarks (end_loads.py, jump_rotation.py): grids, models, horizons and model
options, ``-o key=value`` (pd-bond-pair's variant and ends)."""

from __future__ import annotations

import argparse


def parse(doc: str, points: list[int], models: list[str]) -> tuple[argparse.Namespace, dict]:
    """(the arguments, the model options as a dict) of a benchmark whose docstring is ``doc``."""
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("--points", type=int, nargs="+", default=points)
    ap.add_argument("--models", nargs="+", default=models)
    ap.add_argument("--horizons", type=float, nargs="+", default=[3.0, 5.0])
    ap.add_argument("-o", "--option", action="append", default=[], help="model option key=value (repeatable)")
    args = ap.parse_args()
    return args, dict(kv.split("=", 1) for kv in args.option)
