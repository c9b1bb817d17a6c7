"""Print docs/verify.md's table of the cards from a study's verify folder (the main job: reports/papers/verify)."""

import argparse
import json
from pathlib import Path

COLUMNS = {
    "order": "convergence (straight)",
    "accuracy": "error at the finest grid",
    "locking": "locking (error vs slenderness 5 ... 10000)",
    "round-off": "accuracy floor (round-off)",
    "symmetry": "symmetry (mirror scenes)",
    "superposition": "superposition (two loads vs their sum)",
    "curved": "convergence (curved axes)",
    "dynamics": "dynamics (natural frequencies)",
}


def row(card: dict) -> list[str]:
    checks = {c["check"]: c for c in card["checks"]}
    opts = " ".join(f"{k}={v}" for k, v in card["options"].items())
    cells = [f"{card['model']} ({opts})" if opts else card["model"], f"**{card['verdict']}**"]
    cells += [checks[name]["verdict"] if name in checks else "–" for name in COLUMNS.values()]
    conv, acc = checks.get(COLUMNS["order"], {}), checks.get(COLUMNS["accuracy"], {})
    low = conv.get("lowest_order")
    cells.append(f"{low:.2f}" if low is not None else "exact" if conv.get("verdict") == "pass" else "–")
    big = acc.get("largest")
    cells.append("–" if big is None else f"{big:.1e}")
    pts = checks.get("grids within 1 % and 0.1 %", {}).get("points", {})
    cells.append(" / ".join(str(pts.get(k) or "–") for k in ("0.01", "0.001")))
    return cells


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("folder", type=Path, help="a study's verify folder (holds one folder per card)")
    args = ap.parse_args()
    for f in sorted(args.folder.glob("*/card.json")):
        print("| " + " | ".join(row(json.loads(f.read_text()))) + " |")


if __name__ == "__main__":
    main()
