"""The report card of a verification: card.json, card.html and junit.xml."""

from __future__ import annotations

import html
import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

from ..core.errors import OutputError


def _plain(v):
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, dict):
        return {str(k): _plain(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    return v


def junit(card: dict) -> str:
    """One testcase per check: a failure element when it fails, skipped when not applicable."""
    suite = ET.Element(
        "testsuite",
        name=f"pdverify.verify.{card['model']}",
        tests=str(len(card["checks"])),
        failures=str(sum(c["verdict"] == "fail" for c in card["checks"])),
        skipped=str(sum(c["verdict"] == "n/a" for c in card["checks"])),
        time=f"{card['wall_s']:.3f}",
    )
    for c in card["checks"]:
        case = ET.SubElement(suite, "testcase", classname=f"pdverify.verify.{card['model']}", name=c["check"])
        if c["verdict"] == "fail":
            ET.SubElement(case, "failure", message=c["summary"]).text = c["summary"]
        elif c["verdict"] == "n/a":
            ET.SubElement(case, "skipped", message=c["summary"])
        else:
            ET.SubElement(case, "system-out").text = c["summary"]
    return ET.tostring(ET.ElementTree(suite).getroot(), encoding="unicode", xml_declaration=True) + "\n"


def _fmt(v, spec=".2e") -> str:
    return "–" if v is None or (isinstance(v, float) and math.isnan(v)) else format(v, spec)


def check_anchor(check: str) -> str:
    """The id of a check's row on card.html ('check-convergence-straight'): the study report links to it."""
    return "check-" + (re.sub(r"[^a-z0-9]+", "-", check.lower()).strip("-") or "x")


def page(card: dict) -> str:
    e = html.escape
    opts = ", ".join(f"{k}={v}" for k, v in card["options"].items()) or "defaults"
    rows = "".join(
        f"<tr id='{check_anchor(c['check'])}' class='{c['verdict'].replace('/', '')}'><td>{e(c['check'])}</td>"
        f"<td>{c['verdict']}</td>"
        f"<td>{e(c['summary'])}</td></tr>"
        for c in card["checks"]
    )
    head = "".join(f"<th>{p}</th>" for p in card["grids"])
    scenes = "".join(
        f"<tr><td>{e(s['name'])}</td><td>{_fmt(s['slenderness'], 'g')}</td>"
        + "".join(f"<td>{_fmt(dict(zip(s['points'], s['errors'], strict=True)).get(p))}</td>" for p in card["grids"])
        + f"<td>{' '.join(_fmt(o, '.2f') for o in s['pair_orders'])}</td><td>{_fmt(s['order'], '.2f')}</td>"
        f"<td>{e('; '.join(s['failed']))}</td></tr>"
        for s in card["scenes"]
    )
    skipped = (
        "<h2>Scenes the model declines</h2><ul>" + "".join(f"<li>{e(x)}</li>" for x in card["skipped"]) + "</ul>"
        if card.get("skipped")
        else ""
    )
    also = f" and {e(card['curved_reference'])}" if card["curved_reference"] else ""
    q = e(card.get("measures", "w"))  # what the errors are of (w; a rod's u, a torsion bar's twist)
    return f"""<!doctype html><html><head><meta charset="utf-8"><title>pdverify verify {e(card["model"])}</title>
<style>body{{font-family:sans-serif;margin:2em}} table{{border-collapse:collapse}} td,th{{border:1px solid #ccc;
padding:2px 8px;text-align:right}} td:first-child,th:first-child,.checks td,.checks th{{text-align:left}}
.pass td:nth-child(2){{color:#080}} .fail td:nth-child(2){{color:#c00;font-weight:bold}}</style></head><body>
<h1>{e(card["model"])}: {card["verdict"].upper()}</h1>
<p>{e(card["title"])} ({e(opts)}); theory {e(card["theory"])}, reference {e(card["reference"])}{also}.
Suite {card["suite_version"]}, pdverify {card["pdverify_version"]};
{card["cases"]} cases ({card["failed_cases"]} failed, {card.get("suspect_cases", 0)} suspect: round-off
bound above 1e-6, their measured errors judged), {card["wall_s"]:.1f} s.
Expected order {card["expected_order"]:g}. Error: max |{q} - {q}_ref| / max |{q}_ref| at the model's points.</p>
<h2>Checks</h2><table class="checks"><tr><th>check</th><th>verdict</th><th>measured</th></tr>{rows}</table>
<h2>Scenes</h2><p>Relative error at each grid (points), the orders between successive grids and the fitted order.</p>
<table><tr><th>scene</th><th>L/h</th>{head}<th>orders per pair</th><th>fitted</th><th>failures</th></tr>
{scenes}</table>{skipped}</body></html>
"""


def write_card(card: dict, out: Path) -> None:
    try:
        out.mkdir(parents=True, exist_ok=True)
        (out / "card.json").write_text(json.dumps(_plain(card), indent=1) + "\n")
        (out / "card.html").write_text(page(card))
        (out / "junit.xml").write_text(junit(card))
    except OSError as exc:
        raise OutputError(
            f"{out}: cannot write the report card ({exc.strerror or exc}); choose another --out"
        ) from None
